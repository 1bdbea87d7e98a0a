#!/usr/bin/env python3
"""Checks the relative links and images of markdown files: the target exists and, for
`file.md#anchor`, the anchor is a heading of that file (GitHub's slugs).

Usage: check_links.py PATH...   (files, or folders searched for *.md)
Prints one line per broken link, `FILE:LINE: target: why`, and exits 1 if there is any.
Links inside code blocks and code spans are not links and are skipped; so are URLs.
"""
import os
import re
import sys

LINK = re.compile(r'!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')


def strip_code(line, in_fence):
    """The line without code spans, and whether a fence is open after it."""
    if line.lstrip().startswith('```'):
        return '', not in_fence
    if in_fence:
        return '', True
    return re.sub(r'`[^`]*`', '', line), False


def slugs(path, cache={}):
    """GitHub's anchors of a markdown file's headings."""
    if path not in cache:
        seen = {}
        result = set()
        in_fence = False
        with open(path, encoding='utf-8') as f:
            for line in f:
                if line.lstrip().startswith('```'):
                    in_fence = not in_fence
                    continue
                m = None if in_fence else re.match(r'^#{1,6}\s+(.*?)\s*#*\s*$', line)
                if not m:
                    continue
                text = m.group(1).lower()
                slug = re.sub(r'[^\w\- ]', '', text).replace(' ', '-')
                n = seen.get(slug, 0)
                seen[slug] = n + 1
                result.add(slug if n == 0 else f'{slug}-{n}')
        cache[path] = result
    return cache[path]


def check(path):
    problems = []
    in_fence = False
    with open(path, encoding='utf-8') as f:
        lines = f.readlines()
    for number, raw in enumerate(lines, 1):
        line, in_fence = strip_code(raw, in_fence)
        for m in LINK.finditer(line):
            target = m.group(1)
            if re.match(r'^[a-z][a-z0-9+.-]*:', target):
                continue  # a URL (https:, mailto:)
            file_part, _, anchor = target.partition('#')
            where = (os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                     if file_part else path)
            if not os.path.exists(where):
                problems.append(f'{path}:{number}: {target}: no such file')
            elif anchor and where.endswith('.md') and anchor not in slugs(where):
                problems.append(f'{path}:{number}: {target}: no heading with this anchor')
    return problems


def main(argv):
    files = []
    for arg in argv:
        if os.path.isdir(arg):
            for folder, _, names in os.walk(arg):
                files += [os.path.join(folder, n) for n in sorted(names) if n.endswith('.md')]
        else:
            files.append(arg)
    problems = [p for f in sorted(files) for p in check(f)]
    for p in problems:
        print(p)
    print(f'check_links: {len(files)} files, {len(problems)} broken links', file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))

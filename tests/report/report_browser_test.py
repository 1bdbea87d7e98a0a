#!/usr/bin/env python3
"""`ocpbench report` in a real browser (Debian's chromium and chromium-driver, python3-selenium).

Runs a small suite (tests/report/small-suite.json) once as BASE, copies it as NEW with one
case made worse (its J fine raised by half: a cost regression `ocpbench compare` must find),
draws NEW's figures (results/plot.py), writes the site of BASE NEW, and checks in headless
Chromium that
  - every page (the index, each problem page, the compare view) renders with no console error;
  - the index's table holds every case of the records, one row each;
  - filtering by a method shows exactly that method's cases (derived.jsonl's method_label);
  - sorting by CPU orders the visible rows by the records' cpu_seconds, both ways;
  - every link and image of every page resolves (files exist, images decode);
  - the compare view lists the injected regression first.
Screenshots of the index and of a problem page go to --screenshots.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.parse

from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.common.exceptions import TimeoutException
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def read_jsonl(path):
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def make_results(args, work):
    base, new = os.path.join(work, "base"), os.path.join(work, "new")
    subprocess.run([args.ocpbench, "run", args.suite, "--out", base, "--overwrite"], check=True,
                   stdout=subprocess.DEVNULL)
    shutil.copytree(base, new)
    # The injected regression: the first converged case's cost raised by half in NEW.
    records = read_jsonl(os.path.join(new, "records.jsonl"))
    victim = next(r for r in records if r["status"] == "converged")
    victim["J_fine"] *= 1.5
    victim["Jbar_fine"] *= 1.5
    with open(os.path.join(new, "records.jsonl"), "w", encoding="utf-8") as f:
        for r in records:
            f.write(json.dumps(r) + "\n")
    subprocess.run([sys.executable, args.plot, new], check=True, stdout=subprocess.DEVNULL)
    site = os.path.join(work, "site")
    subprocess.run([args.ocpbench, "report", base, new, "--out", site], check=True)
    return new, site, victim["key"]


def browser():
    options = Options()
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--window-size=1400,1000", "--allow-file-access-from-files"):
        options.add_argument(flag)
    options.binary_location = "/usr/bin/chromium"
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def load(driver, path):
    driver.get("file://" + urllib.parse.quote(os.path.abspath(path)))
    try:
        WebDriverWait(driver, 10).until(
            lambda d: d.execute_script("return document.body.dataset.ready === 'true'"))
    except TimeoutException:
        fail(f"{path}: the page's script did not finish: {driver.get_log('browser')}")
    errors = [e for e in driver.get_log("browser") if e["level"] in ("SEVERE", "ERROR")]
    check(not errors, f"{path}: console errors: {errors}")


def check_links(driver, page):
    """Every link and image of the page resolves: a file of the site, an anchor, an image that
    decoded. Returns the HTML pages linked."""
    folder = os.path.dirname(os.path.abspath(page))
    pages = set()
    hrefs = driver.execute_script(
        "return [...document.querySelectorAll('a[href]')].map(a => a.getAttribute('href'))")
    for href in hrefs:
        check(not href.startswith(("http:", "https:", "//")), f"{page}: link to the network {href}")
        target = urllib.parse.unquote(href.split("#")[0])
        if not target:
            continue
        path = os.path.join(folder, target)
        check(os.path.isfile(path), f"{page}: link {href} resolves to no file")
        if path.endswith(".html"):
            pages.add(os.path.normpath(path))
    images = driver.execute_script(
        "return [...document.querySelectorAll('img')].map(i => [i.getAttribute('src'), "
        "i.complete, i.naturalWidth])")
    for src, _, _ in images:
        check(os.path.isfile(os.path.join(folder, urllib.parse.unquote(src))),
              f"{page}: image {src} resolves to no file")
    # Images load lazily: scroll each into view and wait until it decoded.
    driver.execute_script("document.querySelectorAll('img').forEach(i => i.loading = 'eager')")
    WebDriverWait(driver, 10).until(lambda d: d.execute_script(
        "return [...document.querySelectorAll('img')].every(i => i.complete)"))
    broken = driver.execute_script(
        "return [...document.querySelectorAll('img')].filter(i => i.naturalWidth === 0)"
        ".map(i => i.getAttribute('src'))")
    check(not broken, f"{page}: images that do not decode: {broken}")
    return pages


def screenshot(driver, path):
    """The whole page (the window made as tall as the page, up to 5000 px), from its top."""
    height = driver.execute_script("return document.documentElement.scrollHeight")
    driver.set_window_size(1400, min(max(height, 1000), 5000))
    driver.execute_script("window.scrollTo(0, 0)")
    driver.save_screenshot(path)
    driver.set_window_size(1400, 1000)


def visible_keys(driver):
    return driver.execute_script(
        "return [...document.querySelectorAll('#cases tbody tr')].map(r => r.dataset.key)")


def test_index(driver, new, site):
    index = os.path.join(site, "index.html")
    load(driver, index)
    records = read_jsonl(os.path.join(new, "records.jsonl"))
    derived = read_jsonl(os.path.join(new, "derived.jsonl"))
    keys = visible_keys(driver)
    check(sorted(keys) == sorted(r["key"] for r in records),
          f"the table holds {len(keys)} rows, the records {len(records)} cases")
    # Filtering by a method: exactly that method's cases.
    method = derived[-1]["method_label"]
    Select(driver.find_element(By.ID, "filter-method")).select_by_value(method)
    want = sorted(d["key"] for d in derived if d["method_label"] == method)
    check(sorted(visible_keys(driver)) == want,
          f"filter by method {method!r}: rows {visible_keys(driver)}, expected {want}")
    check(len(want) < len(records), "the method filter hid nothing (a weak test)")
    Select(driver.find_element(By.ID, "filter-method")).select_by_value("")
    check(len(visible_keys(driver)) == len(records), "clearing the filter shows every case again")
    # Sorting by CPU, then the other way; cases without a CPU time sort last either way.
    cpu = {r["key"]: r.get("cpu_seconds") for r in records}
    timed = [k for k in cpu if cpu[k] is not None]
    header = driver.find_element(By.CSS_SELECTOR, "#cases th[data-key='cpu']")
    header.click()
    rows = visible_keys(driver)
    check(rows[:len(timed)] == sorted(timed, key=lambda k: cpu[k]),
          "sorting by CPU (ascending) does not order the rows by cpu_seconds")
    header.click()
    rows = visible_keys(driver)
    check(rows[:len(timed)] == sorted(timed, key=lambda k: -cpu[k]),
          "sorting by CPU again (descending) does not reverse the order")
    screenshot(driver, os.path.join(args.screenshots, "index.png"))
    return check_links(driver, index)


def test_compare(driver, site, victim):
    page = os.path.join(site, "compare.html")
    load(driver, page)
    first = driver.execute_script(
        "const r = document.querySelector('#compare-cases tbody tr');"
        "return [r.className, r.cells[0].textContent, r.cells[4].textContent]")
    check(first[0] == "verdict-regressed" and first[1] == "regressed",
          f"the compare view's first row is {first}, not the injected regression")
    check("cost" in first[2], f"the first row's findings {first[2]!r} do not name the cost")
    regressed = driver.execute_script(
        "return [...document.querySelectorAll('#compare-cases tbody tr.verdict-regressed')].length")
    check(regressed == 1, f"{regressed} regressed rows, the test injected one ({victim})")
    check_links(driver, page)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--ocpbench", required=True)
    parser.add_argument("--suite", required=True)
    parser.add_argument("--plot", required=True, help="results/plot.py")
    parser.add_argument("--work", required=True, help="a scratch folder (emptied first)")
    parser.add_argument("--screenshots", required=True)
    args = parser.parse_args()
    started = time.monotonic()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    os.makedirs(args.screenshots, exist_ok=True)
    new, site, victim = make_results(args, args.work)
    driver = browser()
    try:
        pages = test_index(driver, new, site)
        problems = sorted(p for p in pages if os.path.basename(p).startswith("problem-"))
        check(problems, "the index links no problem page")
        for k, page in enumerate(problems):
            load(driver, page)
            svgs = driver.execute_script("return document.querySelectorAll('svg.chart path').length")
            check(svgs > 0, f"{page}: no curve drawn")
            if k == 0:
                screenshot(driver, os.path.join(args.screenshots, "problem.png"))
            check_links(driver, page)
        test_compare(driver, site, victim)
    finally:
        driver.quit()
    print(f"report_browser: {len(problems) + 2} pages checked in "
          f"{time.monotonic() - started:.1f} s; screenshots in {args.screenshots}")

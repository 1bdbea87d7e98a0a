"""Writing figures atomically: a killed or failing run never leaves a half-written PNG under the
final name (readers, such as the README's links, see the old figure or the new one)."""
import os


def save_figure(fig, path, **savefig_args):
    """fig.savefig to a temporary name in path's directory, then os.replace onto path."""
    directory, name = os.path.split(os.path.abspath(path))
    stem, ext = os.path.splitext(name)
    tmp = os.path.join(directory, ".%s.tmp-%d%s" % (stem, os.getpid(), ext))
    try:
        fig.savefig(tmp, format=ext.lstrip(".") or "png", **savefig_args)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)

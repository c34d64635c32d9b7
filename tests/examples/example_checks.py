"""What every example check shares (``from example_checks import attr, check, finish``):
a results attribute read as text whatever h5py returns, one ``ok``/``FAIL`` line per
check, and the failure count with the exit status at the end."""
import sys

fails = []


def attr(f, name):
    """Root or object attribute `name` of an h5py object; bytes decoded."""
    v = f.attrs[name]
    return v.decode() if isinstance(v, bytes) else v


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        fails.append(what)


def finish():
    print(f"{len(fails)} failure(s)")
    sys.exit(1 if fails else 0)

#!/usr/bin/env python3
"""Where the page's code bytes go, from the wasm's name section (docs/web.md, "A lighter page").

wasm-bindgen strips the name section, so read the wasm cargo leaves before it:
    python3 web/measure/wasm_crates.py target/wasm32-unknown-unknown/web/rigidlab.wasm [TOP]
Prints the code bytes per crate (the first path segment of each function's mangled name; a trait
impl counts under its `<Type as Trait>` text), and the second physics copy: the functions whose
name mentions rapier2d_f64, parry2d_f64 or rigidlab::sim64, their bytes raw and zstd -19 alone
(compressed apart from the rest, so an estimate of what they add on the wire). Standard library
only, plus the `zstd` command for the compressed figure."""
import collections
import re
import subprocess
import sys


def leb(b, i):
    """An unsigned LEB128 at i: (value, index after it)."""
    r = s = 0
    while True:
        x = b[i]
        i += 1
        r |= (x & 0x7F) << s
        s += 7
        if x < 0x80:
            return r, i


def sections(b):
    """(id, start, end) of each section after the 8-byte header."""
    i = 8
    while i < len(b):
        sid = b[i]
        n, i = leb(b, i + 1)
        yield sid, i, i + n
        i += n


def imported_functions(b, s):
    """How many functions the import section brings (they take the first function indices)."""
    cnt, i = leb(b, s)
    n = 0
    for _ in range(cnt):
        for _ in range(2):  # module and field names
            ln, i = leb(b, i)
            i += ln
        kind = b[i]
        i += 1
        if kind == 0:  # function: a type index
            _, i = leb(b, i)
            n += 1
        elif kind == 1:  # table: a reference type, then limits
            flags, i = leb(b, i + 1)
            _, i = leb(b, i)
            if flags & 1:
                _, i = leb(b, i)
        elif kind == 2:  # memory: limits
            flags, i = leb(b, i)
            _, i = leb(b, i)
            if flags & 1:
                _, i = leb(b, i)
        elif kind == 3:  # global: a value type and mutability
            i += 2
    return n


def function_names(b, i, end):
    """The name section's function names subsection (id 1): index -> mangled name."""
    names = {}
    while i < end:
        sub = b[i]
        ln, i = leb(b, i + 1)
        if sub == 1:
            cnt, j = leb(b, i)
            for _ in range(cnt):
                idx, j = leb(b, j)
                ln2, j = leb(b, j)
                names[idx] = b[j : j + ln2].decode("utf-8", "replace")
                j += ln2
        i += ln
    return names


def functions(path):
    """(name, body bytes) of every function defined in the wasm."""
    b = open(path, "rb").read()
    nimp, bodies, names = 0, [], {}
    for sid, s, e in sections(b):
        if sid == 2:
            nimp = imported_functions(b, s)
        elif sid == 10:
            cnt, i = leb(b, s)
            for _ in range(cnt):
                ln, i = leb(b, i)
                bodies.append(b[i : i + ln])
                i += ln
        elif sid == 0:
            ln, i = leb(b, s)
            if b[i : i + ln] == b"name":
                names = function_names(b, i + ln, e)
    if not names:
        sys.exit(f"{path}: no name section (wasm-bindgen removes it: read the wasm cargo built)")
    return [(names.get(nimp + k, "?"), body) for k, body in enumerate(bodies)]


def crate_of(name):
    """The first path segment of a legacy-mangled Rust name (_ZN<len><ident>...)."""
    m = re.match(r"_ZN(\d+)", name)
    if not m:
        return name.split("::")[0]
    return name[3 + len(m.group(1)) :][: int(m.group(1))]


F64_COPY = re.compile(r"rapier2d_f64|parry2d_f64|8rigidlab5sim64")


def zstd_size(data):
    return len(subprocess.run(["zstd", "-19", "-q", "-c"], input=data, capture_output=True, check=True).stdout)


def main():
    fns = functions(sys.argv[1])
    top = int(sys.argv[2]) if len(sys.argv) > 2 else 25
    total = sum(len(body) for _, body in fns)
    per, count = collections.Counter(), collections.Counter()
    for name, body in fns:
        per[crate_of(name)] += len(body)
        count[crate_of(name)] += 1
    print(f"code: {total} bytes in {len(fns)} functions")
    for crate, size in per.most_common(top):
        print(f"{size:>10} {100 * size / total:5.1f}% {count[crate]:>6}  {crate}")
    f64 = b"".join(body for name, body in fns if F64_COPY.search(name))
    rest = b"".join(body for name, body in fns if not F64_COPY.search(name))
    nf64 = sum(1 for name, _ in fns if F64_COPY.search(name))
    print(
        f"the f64 copy (rapier2d_f64, parry2d_f64, rigidlab::sim64): {len(f64)} bytes in {nf64} functions "
        f"({100 * len(f64) / total:.1f}% of the code), zstd -19 alone {zstd_size(f64)}; "
        f"the rest of the code alone {zstd_size(rest)}"
    )


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""docs/api.md names the whole public API, and nothing else as a function.

usage: check_api_doc.py API_MD --symbols LIST... --headers HEADER...

Fails when docs/api.md does not name
  - a function of an exported-symbol list (tests/libpw85.symbols, ...),
  - a macro PW85_* defined by a public header (include guards excepted),
  - a struct or typedef declared by a public header;
or when it names as a function something that is neither exported nor a
public type: a pw85_* identifier followed by "(" or standing alone in
backquotes (`pw85_foo`). File names such as pw85_legacy.h are not names.
"""
import re
import sys

IDENT = r"[A-Za-z0-9_]"


def mentioned(name, text):
    return re.search(rf"(?<!{IDENT}){re.escape(name)}(?!{IDENT})", text) is not None


def read_symbols(path):
    with open(path) as f:
        return [l.strip() for l in f if l.strip() and not l.lstrip().startswith("#")]


def header_names(path):
    with open(path) as f:
        text = f.read()
    # Include guard: the first #ifndef X directly followed by #define X.
    guard = re.search(r"^\s*#\s*ifndef\s+(\w+)\s*\n\s*#\s*define\s+\1\s*$", text, re.M)
    macros = set(re.findall(r"^\s*#\s*define\s+((?:PW85_)\w+)", text, re.M))
    if guard:
        macros.discard(guard.group(1))
    types = set(re.findall(r"\btypedef\s+struct\s+(\w+)", text))
    types |= set(re.findall(r"^\s*}\s*(\w+)\s*;", text, re.M))
    return macros, types


def main(argv):
    api_md, args = argv[1], argv[2:]
    lists, headers, mode = [], [], None
    for a in args:
        if a in ("--symbols", "--headers"):
            mode = a
        elif mode == "--symbols":
            lists.append(a)
        elif mode == "--headers":
            headers.append(a)
        else:
            print(f"unexpected argument {a!r}")
            return 2
    if not lists or not headers:
        print(__doc__)
        return 2
    with open(api_md) as f:
        text = f.read()

    functions = set()
    for path in lists:
        functions |= set(read_symbols(path))
    macros, types = set(), set()
    for path in headers:
        m, t = header_names(path)
        macros |= m
        types |= t

    errors = []
    for kind, names in (("exported function", functions), ("macro", macros),
                        ("struct/typedef", types)):
        for name in sorted(names):
            if not mentioned(name, text):
                errors.append(f"{api_md} does not name the {kind} {name}")

    named = set(re.findall(rf"(?<!{IDENT})(pw85_\w+)\s*\(", text))
    named |= set(re.findall(r"`(pw85_\w+)`", text))
    for name in sorted(named - functions - types):
        errors.append(f"{api_md} names {name}, which is not exported "
                      "(not in the symbol lists) nor a public type")

    for e in errors:
        print(e)
    print(f"{len(functions)} functions, {len(macros)} macros, {len(types)} types "
          f"checked against {api_md}; {len(named)} names of functions in it:",
          "OK" if not errors else f"{len(errors)} problem(s)")
    if not functions or not macros or not types:
        print("nothing parsed: wrong arguments?")
        return 1
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

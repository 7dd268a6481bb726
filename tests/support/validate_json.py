"""Validates JSON documents against a JSON Schema 2020-12 with an
implementation independent of lmdc, as users' own checks would:
jsonschema-rs (fast) when installed, else Python's jsonschema.
`validate_json.py SCHEMA [--lines] FILE...`.

With --lines each line of each file is one document (JSON lines). Prints
`FILE[:LINE]: at PATH: MESSAGE` for each error (at most 20) and exits 1 when
any document is invalid, 2 on a usage error or a schema that is not one."""

import json
import sys

import jsonschema

try:
    import jsonschema_rs
except ImportError:
    jsonschema_rs = None


def deepest(e):
    """The error a oneOf/anyOf failure comes down to: in the branch with the
    fewest errors (a tagged variant's own branch: the others fail on the tag
    and more), the best match, followed down."""
    while e.context:
        branches = {}
        for c in e.context:
            branches.setdefault(c.relative_schema_path[0], []).append(c)
        e = jsonschema.exceptions.best_match(min(branches.values(), key=len))
    return e


def shorten(message):
    """A message that quotes a large value: its start and its end."""
    return message if len(message) <= 400 else message[:150] + " … " + message[-200:]


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    schema_path, rest = argv[0], argv[1:]
    lines = rest[:1] == ["--lines"]
    files = rest[1:] if lines else rest
    with open(schema_path, encoding="utf-8") as f:
        schema = json.load(f)
    try:
        jsonschema.Draft202012Validator.check_schema(schema)
    except jsonschema.SchemaError as e:
        print(f"{schema_path}: not a JSON Schema: {e.message}", file=sys.stderr)
        return 2
    validator = jsonschema.Draft202012Validator(schema)
    fast = jsonschema_rs.validator_for(schema) if jsonschema_rs else None
    errors = 0
    documents = 0
    for name in files:
        with open(name, encoding="utf-8") as f:
            text = f.read()
        docs = (
            [(f"{name}:{i + 1}", l) for i, l in enumerate(text.splitlines()) if l.strip()]
            if lines
            else [(name, text)]
        )
        for where, doc in docs:
            documents += 1
            value = json.loads(doc)
            if fast is not None and fast.is_valid(value):
                continue
            for e in validator.iter_errors(value):
                errors += 1
                if errors <= 20:
                    e = deepest(e)
                    path = "$" + "".join(f"[{p!r}]" for p in e.absolute_path)
                    print(f"{where}: at {path}: {shorten(e.message)}")
    print(f"{documents} documents, {errors} errors", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

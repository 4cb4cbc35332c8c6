#!/usr/bin/env python3
"""The cross-checker reads the CLI's outputs strictly: a lists, table or
max-age CSV row with a missing or extra field, or a bad header, is a failure,
never a silently shortened row (the independent model's side of SPEC 10)."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import crosscheck  # noqa: E402


def expect_failure(text, header, conv, needle):
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write(text)
        path = f.name
    try:
        crosscheck._parse_csv(path, header, conv)
    except crosscheck.CaseFailure as e:
        assert needle in str(e), (needle, str(e))
        return
    finally:
        os.unlink(path)
    raise AssertionError("no failure for %r" % text)


def main():
    lists = ("x,y,rank,code,rgba", (int,) * 5)
    expect_failure("x,y,rank,code,rgba\n0,0,0,5,7,9\n", *lists, ":2: 6 fields")
    expect_failure("x,y,rank,code,rgba\n0,0,0,5\n", *lists, ":2: 4 fields")
    expect_failure("x,y,rank,code\n", *lists, "bad header")
    expect_failure("x,y,rank,code,rgba\n0,0,0,5,seven\n", *lists, "unparsable")
    table = ("slot,record", (int, crosscheck._hex))
    expect_failure("slot,record\n3,0x10,1\n", *table, ":2: 3 fields")
    expect_failure("slot,record\n3,16\n", *table, "unparsable")
    maxage = ("cx,cy,max_age", (int,) * 3)
    expect_failure("cx,cy,max_age\n0,0,1,1\n", *maxage, ":2: 4 fields")
    print("output parsing: 7 cases passed")


if __name__ == "__main__":
    main()

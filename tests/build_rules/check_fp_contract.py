#!/usr/bin/env python3
"""Every file the build compiles carries -ffp-contract=off (issue 47, part 5).

The CPU path agrees with the GPU path bit for bit only when neither fuses a
multiply and an add the other does not. The flag comes with habuffer_build_flags,
which habuffer_add_library and habuffer_add_executable always link
(cmake/HabufferTargets.cmake); a target made any other way without it shows
here as the files it compiles.

usage: check_fp_contract.py BUILD_DIR
"""

import json
import os
import sys


def main():
    build = os.path.abspath(sys.argv[1])
    path = os.path.join(build, "compile_commands.json")
    if not os.path.exists(path):
        print("SKIP: %s not written (CMAKE_EXPORT_COMPILE_COMMANDS is on only where the project is top level)" % path)
        return 77
    with open(path) as f:
        entries = json.load(f)
    missing = []
    for e in entries:
        command = e.get("command") or " ".join(e.get("arguments", []))
        if "-ffp-contract=off" not in command.split():
            missing.append(os.path.relpath(e["file"], e.get("directory", build)))
    for m in missing[:20]:
        print("compiled without -ffp-contract=off: " + m)
    print("%d compiled files, %d without -ffp-contract=off" % (len(entries), len(missing)))
    if len(entries) < 20:
        print("too few compiled files to mean anything: is this the project's build folder?")
        return 1
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Checks each workspace crate's `rust-version` against its locked dependencies.

For every workspace member, the largest `rust-version` declared by any crate
in its transitive normal and build dependencies (as locked in Cargo.lock) is
a lower bound of the toolchain the member really needs. The declared
`rust-version` must be at least that bound; it may not claim an older
toolchain than its dependencies accept. (Use of newer standard-library APIs
in our own code is checked by clippy's `incompatible_msrv` lint, which reads
the same field.) Prints the table; exits 1 on a violation.
"""
import json
import subprocess
import sys


def version(v):
    parts = [int(x) for x in (v or "0").split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def main():
    meta = json.loads(
        subprocess.check_output(
            ["cargo", "metadata", "--format-version", "1", "--locked"]
        )
    )
    pkgs = {p["id"]: p for p in meta["packages"]}
    nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}

    def closure(root, with_dev):
        seen, stack = set(), [root]
        while stack:
            pid = stack.pop()
            for dep in nodes[pid]["deps"]:
                kinds = {k["kind"] for k in dep["dep_kinds"]}
                if not with_dev or pid != root:
                    kinds.discard("dev")
                if kinds and dep["pkg"] not in seen:
                    seen.add(dep["pkg"])
                    stack.append(dep["pkg"])
        return seen

    bad = 0
    for mid in meta["workspace_members"]:
        member = pkgs[mid]
        declared = member.get("rust_version")
        for with_dev, what in ((False, "dependencies"), (True, "with dev-dependencies")):
            deps = closure(mid, with_dev)
            need, who = max(
                ((version(pkgs[d].get("rust_version")), pkgs[d]["name"]) for d in deps),
                default=((0,), "none"),
            )
            need_s = ".".join(map(str, need))
            ok = declared is not None and version(declared) >= need
            # Dev-dependencies only bind those who run our tests: report them,
            # fail only on the normal and build dependencies.
            if not ok and not with_dev:
                bad += 1
            print(
                f"{member['name']:14} declares {declared or 'nothing':6} "
                f"{what:24} need {need_s:6} ({who}){'' if ok or with_dev else '  <-- too old'}"
            )
    if bad:
        print(f"{bad} crate(s) declare a rust-version older than their dependencies need")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

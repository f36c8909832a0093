#!/usr/bin/env python3
"""Checks each workspace crate's `rust-version` against its locked dependencies.

For every workspace member, the largest `rust-version` declared by any crate
in its transitive normal and build dependencies (as locked in Cargo.lock) is
a lower bound of the toolchain the member really needs. The declared
`rust-version` must be at least that bound; it may not claim an older
toolchain than its dependencies accept. (Use of newer standard-library APIs
in our own code is checked by clippy's `incompatible_msrv` lint, which reads
the same field.) Prints the table; exits 1 on a violation.

The optional features of `dymsum` may need a newer toolchain than the crate
(their dependencies do); FEATURE_MSRV states what docs/RUST.md and the
manifest say each needs, and the check fails when that claim is lower than
what the feature's locked dependencies declare.
"""
import json
import subprocess
import sys


def version(v):
    parts = [int(x) for x in (v or "0").split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


# The toolchain each optional feature of `dymsum` needs, as documented in
# docs/RUST.md ("The minimum supported Rust is ...") and crates/dymsum/Cargo.toml.
FEATURE_MSRV = {"parry": "1.90", "nalgebra": "1.89", "mint": "1.85", "serde": "1.85"}


def metadata(features=None):
    cmd = ["cargo", "metadata", "--format-version", "1", "--locked"]
    if features:
        cmd += ["--features", features]
    return json.loads(subprocess.check_output(cmd))


def need_of(meta, name):
    """The largest rust-version in the normal dependencies of crate `name`."""
    pkgs = {p["id"]: p for p in meta["packages"]}
    nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}
    root = next(i for i in meta["workspace_members"] if pkgs[i]["name"] == name)
    seen, stack = set(), [root]
    while stack:
        for dep in nodes[stack.pop()]["deps"]:
            kinds = {k["kind"] for k in dep["dep_kinds"]} - {"dev"}
            if kinds and dep["pkg"] not in seen:
                seen.add(dep["pkg"])
                stack.append(dep["pkg"])
    return max(
        ((version(pkgs[d].get("rust_version")), pkgs[d]["name"]) for d in seen),
        default=((0,), "none"),
    )


def check_features():
    bad = 0
    for feature, claimed in FEATURE_MSRV.items():
        need, who = need_of(metadata(f"dymsum/{feature}"), "dymsum")
        ok = version(claimed) >= need
        bad += not ok
        print(
            f"dymsum feature {feature:9} documented {claimed:6} "
            f"need {'.'.join(map(str, need)):6} ({who}){'' if ok else '  <-- documented too old'}"
        )
    return bad


def main():
    meta = metadata()
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
    bad += check_features()
    if bad:
        print(f"{bad} crate(s) or feature(s) declare a rust-version older than their dependencies need")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

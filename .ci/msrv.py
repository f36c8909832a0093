#!/usr/bin/env python3
"""Checks each workspace crate's `rust-version` against its locked dependencies.

For every workspace member, the largest `rust-version` declared by any crate
in its transitive normal and build dependencies (as locked in Cargo.lock,
with the features that member alone turns on: `cargo tree -p MEMBER`, not
the workspace-wide unification of `cargo metadata`, where one member turning
on an optional feature of another would charge its dependencies to both) is
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
FEATURE_MSRV = {"parry": "1.90", "nalgebra": "1.89", "union-mesh": "1.88", "mint": "1.85", "serde": "1.85"}


def metadata(features=None):
    cmd = ["cargo", "metadata", "--format-version", "1", "--locked"]
    if features:
        cmd += ["--features", features]
    return json.loads(subprocess.check_output(cmd))


def tree(name, features=None, dev=False):
    """The (name, version) of every crate `name` depends on, built alone
    (`cargo tree -p NAME`: features resolved for that package only), through
    normal and build edges (and its own dev-dependencies with `dev`)."""
    edges = "normal,build,dev" if dev else "normal,build"
    cmd = ["cargo", "tree", "--locked", "-p", name, "-e", edges, "--prefix", "none", "--target", "all"]
    if features:
        cmd += ["--features", features]
    out = set()
    # The first line is `name` itself.
    for line in subprocess.check_output(cmd, text=True).splitlines()[1:]:
        parts = line.split()
        if len(parts) >= 2 and parts[1].startswith("v") and not line.startswith("["):
            out.add((parts[0], parts[1][1:]))
    return out


def need_of(meta, name, features=None, dev=False):
    """The largest rust-version in the dependencies of crate `name`."""
    rust = {(p["name"], p["version"]): p.get("rust_version") for p in meta["packages"]}
    return max(
        ((version(rust.get(d)), d[0]) for d in tree(name, features, dev)),
        default=((0,), "none"),
    )


def check_features(meta):
    bad = 0
    for feature, claimed in FEATURE_MSRV.items():
        need, who = need_of(meta, "dymsum", feature)
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
    bad = 0
    for mid in meta["workspace_members"]:
        member = pkgs[mid]
        declared = member.get("rust_version")
        for with_dev, what in ((False, "dependencies"), (True, "with dev-dependencies")):
            need, who = need_of(meta, member["name"], dev=with_dev)
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
    bad += check_features(meta)
    if bad:
        print(f"{bad} crate(s) or feature(s) declare a rust-version older than their dependencies need")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The README's first two commands share their dependency builds (issue 29).

`cargo run --release -p dymsum-cli -- demo` resolves the features of its
dependencies over the CLI alone; `cargo test --workspace --release` (the
first pass of scripts/test.sh) over every member with its dev-dependencies,
and `cargo test -p dymsum --features check-reference` (its second pass) over
dymsum with its dev-dependencies. A dependency that one of them builds with
other features than the workspace's tests is compiled again, with
everything above it. This checks, with `cargo tree`, that every
(package, features) the demo or the second pass builds is one the
workspace's tests build too (dymsum itself excepted in the second pass: its
`check-reference` feature is the point). Fix a failure by naming the
missing features in crates/dymsum-cli/Cargo.toml (the demo) or
crates/dymsum-testkit/Cargo.toml (the second pass, through dymsum's
dev-dependency on the testkit).
"""

import subprocess
import sys


def tree(*args):
    out = subprocess.check_output(
        ["cargo", "tree", "--locked", *args, "-f", "{p} {f}", "--prefix", "none"], text=True
    )
    return {line.removesuffix(" (*)").strip() for line in out.splitlines() if line.strip()}


def main():
    workspace = tree("--workspace", "-e", "normal,build,dev")
    checks = [
        ("cargo run --release -p dymsum-cli (the demo)", tree("-p", "dymsum-cli", "-e", "normal,build"), None),
        (
            "cargo test -p dymsum --features check-reference",
            tree("-p", "dymsum", "--features", "check-reference", "-e", "normal,build,dev"),
            "dymsum v",
        ),
    ]
    failed = False
    for name, units, exempt in checks:
        extra = sorted(u for u in units - workspace if not (exempt and u.startswith(exempt)))
        if extra:
            failed = True
            print(f"{name} builds these with features the workspace's tests do not use:", file=sys.stderr)
            for u in extra:
                print(f"  {u}", file=sys.stderr)
        else:
            print(f"{name}: every dependency as the workspace's tests build it")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

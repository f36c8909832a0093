//! Issue 26 §6 through the binary: nothing is lost on a kill. A forced
//! `cobst` run killed while it computes or writes leaves the earlier output
//! intact (or, past its commit point, the new output complete); the next
//! run removes the temporary entries of killed runs, keeps a running
//! process's, and never counts them when deciding a folder is not empty.
//! (The deterministic abort at each step of the swap and a writer failing
//! after k bytes for every k are unit tests of `dymsum_io::staging` and
//! `dymsum_io::atomic`; python/benchmarks/bench_kill.py kills at random.)

mod common;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{ok, temp_dir, BIN};

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The files of `dir` that are not temporary entries (`.`-names), with
/// their bytes; and whether a ready folder (a committed swap the next run
/// finishes) is there.
fn files(dir: &Path) -> (BTreeMap<String, Vec<u8>>, bool) {
    let mut out = BTreeMap::new();
    let mut ready = false;
    for e in std::fs::read_dir(dir).unwrap() {
        let e = e.unwrap();
        let name = e.file_name().into_string().unwrap();
        if name.starts_with(".dymsum-ready-") {
            ready = true;
        }
        if !name.starts_with('.') {
            out.insert(name, std::fs::read(e.path()).unwrap());
        }
    }
    (out, ready)
}

/// Every entry name of `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    v.sort();
    v
}

/// Starts `dymsum ARGS` and SIGKILLs it after `ms` milliseconds (or lets
/// it finish first); waits for it, so its process id is dead afterwards.
fn run_and_kill(args: &[&str], ms: u64) {
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(ms));
    let _ = child.kill();
    child.wait().unwrap();
}

fn cobst<'a>(slices: &'a str, format: &'a str, out: &'a Path) -> Vec<&'a str> {
    vec![
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        slices,
        "--format",
        format,
        "--out",
        s(out),
        "--force",
    ]
}

/// Kills forced runs replacing a small earlier output with a large one at
/// several moments; after each, the earlier output is intact or the new
/// one complete (a committed swap counts: the next run finishes it); a
/// last uninterrupted run leaves no temporary entry. Before issue 26
/// `--force` removed the earlier files first, so a kill while computing
/// left nothing.
fn kill_forced_runs(format: &str, big: &str) {
    let dir = temp_dir(&format!("kill-{format}"));
    let out = dir.join("out");
    ok(&cobst("3", format, &out));
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let (old, _) = files(&out);
    // The complete new output, from an uninterrupted run elsewhere.
    let fresh = dir.join("fresh");
    ok(&cobst(big, format, &fresh));
    let (mut new, _) = files(&fresh);
    new.insert("notes.txt".into(), b"mine".to_vec());
    for ms in [40, 120, 250, 500] {
        run_and_kill(&cobst(big, format, &out), ms);
        let (now, ready) = files(&out);
        assert!(
            now == old || now == new || ready,
            "killed after {ms} ms: neither the earlier nor the new output: {:?}",
            now.keys().take(8).collect::<Vec<_>>()
        );
    }
    ok(&cobst(big, format, &out));
    assert_eq!(files(&out), (new, false));
    assert!(
        names(&out).iter().all(|n| !n.starts_with('.')),
        "{:?}",
        names(&out)
    );
}

#[test]
fn a_killed_forced_npz_run_keeps_the_earlier_map() {
    kill_forced_runs("npz", "6000");
}

#[test]
fn a_killed_forced_folder_run_keeps_the_earlier_slices_and_index() {
    kill_forced_runs("halfspaces", "1500");
}

#[test]
fn temporary_entries_of_dead_writers_are_removed_live_ones_kept_and_neither_counted() {
    let dir = temp_dir("temps");
    let out = dir.join("out");
    std::fs::create_dir(&out).unwrap();
    // A process id that is dead: a child that has exited and been reaped.
    let mut child = Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let live = std::process::id();
    let dead_tmp = format!(".map.tmp-{dead}-3.npz");
    let dead_py = format!(".map.tmp-{dead}-k2x_9q.npz");
    let live_tmp = format!(".map.tmp-{live}-0.npz");
    let dead_staging = format!(".dymsum-staging-{dead}-0");
    let live_staging = format!(".dymsum-staging-{live}-7");
    for f in [&dead_tmp, &dead_py, &live_tmp] {
        std::fs::write(out.join(f), "partial").unwrap();
    }
    for d in [&dead_staging, &live_staging] {
        std::fs::create_dir(out.join(d)).unwrap();
        std::fs::write(out.join(d).join("slice_00000.off"), "partial").unwrap();
    }
    // Not "not empty": only temporary entries are there (no --force).
    ok(&[
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        "2",
        "--format",
        "npz",
        "--out",
        s(&out),
    ]);
    let mut want = vec![live_staging, live_tmp, "map.npz".to_string()];
    want.sort();
    if Path::new("/proc/self").exists() && !Path::new("/proc").join(dead.to_string()).exists() {
        assert_eq!(names(&out), want);
    }
    // A killed run's committed swap is finished by the next run: a ready
    // folder holding a new map.npz replaces the earlier one.
    let ready = out.join(format!(".dymsum-ready-{dead}-1"));
    std::fs::create_dir(&ready).unwrap();
    std::fs::write(ready.join("map.npz"), "the new map").unwrap();
    std::fs::write(ready.join(".manifest"), "map.npz\n").unwrap();
    std::fs::write(out.join("index.json"), "an earlier index").unwrap();
    ok(&[
        "cobst",
        "box",
        "gs1",
        "--axis",
        "0,0,1",
        "--slices",
        "2",
        "--format",
        "off",
        "--out",
        s(&out),
        "--force",
    ]);
    if Path::new("/proc/self").exists() && !Path::new("/proc").join(dead.to_string()).exists() {
        assert!(!ready.exists());
        assert!(!out.join("map.npz").exists(), "{:?}", names(&out));
        assert!(out.join("slice_00001.off").is_file());
    }
}

#[test]
fn every_writer_removes_a_killed_writers_temporary_file_beside_its_output() {
    let dir = temp_dir("sum-temps");
    let mut child = Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    let stale = dir.join(format!(".sum.tmp-{dead}-0.off"));
    let live = dir.join(format!(".sum.tmp-{}-0.off", std::process::id()));
    std::fs::write(&stale, "partial").unwrap();
    std::fs::write(&live, "partial").unwrap();
    ok(&["sum", "cube", "gs1", "-o", s(&dir.join("sum.off"))]);
    assert!(dir.join("sum.off").is_file());
    assert!(live.exists(), "a running writer's file is kept");
    if Path::new("/proc/self").exists() && !Path::new("/proc").join(dead.to_string()).exists() {
        assert!(!stale.exists(), "{:?}", names(&dir));
    }
}

//! What the command-line tool writes today, held to the bit: every method's
//! run of the paper's two tasks, of the playground's planar presets and of
//! the arms in space, the paths, an atlas's JSON and CSV, and the figures
//! (SVG). `tests/data/golden.tsv` holds, for each command, two digests of
//! what it printed (or wrote to `--out`): one of the text, byte for byte,
//! and one of the numbers in it, taken as a multiset of their bit patterns,
//! so a file whose keys are renamed or reordered keeps its numbers digest
//! while any number that moves by one bit changes it.
//!
//! This is the guard of the merge of the planar arm and the arms in space
//! into one model (docs/architecture.md): the planar runs must not move by
//! a bit whatever their format's keys become; a change that means to move
//! them says so and writes the file again:
//!
//! ```sh
//! GOLDEN_WRITE=1 cargo test --test golden   # rewrites tests/data/golden.tsv
//! ```
//!
//! A failure lists every command whose output changed and which digest.
//! The digests are this project's machine kind's (x86-64 with AVX2 and
//! FMA): the networks' kernels pick their instructions at run time
//! (`nn::kernel`), so a processor without FMA computes Cases 1-3 to other
//! last bits, and their rows would differ there.
#![cfg(not(target_family = "wasm"))]

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use redundant_ik::planner::methods;

const FILE: &str = "tests/data/golden.tsv";

/// 64-bit FNV-1a: stable across Rust versions and machines (std's hasher
/// is not promised to be).
fn fnv(bytes: impl IntoIterator<Item = u8>) -> u64 {
    bytes.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The numbers of a text: every maximal run that parses as an `f64`
/// (JSON's, CSV's and SVG's numbers alike), as the sorted bit patterns'
/// digest, so it does not depend on the keys around them or their order.
fn numbers_digest(text: &str) -> u64 {
    let mut bits: Vec<u64> = text
        .split(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .filter(|t| t.bytes().any(|b| b.is_ascii_digit()))
        .filter_map(|t| t.parse::<f64>().ok())
        .map(f64::to_bits)
        .collect();
    bits.sort_unstable();
    fnv(bits.iter().flat_map(|b| b.to_le_bytes()))
}

/// Every command, by a name that says what it runs. `{out}` stands for a
/// scratch file whose content is the output (the figures).
fn commands() -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let args = |s: &str| s.split(' ').map(String::from).collect::<Vec<_>>();
    let names: Vec<String> = methods::ALL.iter().map(|m| m.to_string()).collect();
    for m in &names {
        for task in ["1", "2"] {
            out.push(args(&format!("simulate --task {task} --method {m} --json")));
        }
        for arm in ["four", "five", "iiwa-planar"] {
            out.push(args(&format!("simulate --arm {arm} --method {m} --json")));
        }
        for arm in ["panda", "iiwa14"] {
            out.push(args(&format!("simulate --arm {arm} --method {m} --json")));
        }
    }
    for extra in [
        "simulate --task 1 --method case3 --networks reach --refine 4 --feedback 1 --json",
        "simulate --task 1 --method case3 --precision f32 --json",
        "simulate --task 1 --method numerical --joint-weighting wln --arm iiwa-planar --json",
        "simulate --task 1 --method qp --floor --obstacle 1.1,1.3 --obstacle 0.6,0.9,0.08 --json",
        "simulate --task 1 --method numerical --path circle:1.1,1 --json",
        "simulate --task 2 --method distance --path points:1.2,1.2;1.4,0.6 --json",
        "simulate --task 1 --method numerical --target 2.4,1.6 --json",
        "simulate --task 1 --method numerical --csv",
        "simulate --task 1 --method case3",
        "simulate --arm panda --method case3 --networks panda-reach --json",
        "simulate --arm panda --method qp --path circle:0.45,0,0.5,0,0,1 --json",
        "simulate --arm iiwa14 --method distance --path points:0.5,0.1,0.6;0.4,0.3,0.5 --json",
        "simulate --arm panda --method numerical --target 2,0,0.5 --json",
        "simulate --arm panda --method qp --csv",
        "atlas --task 1 --grid 9 --json",
        "atlas --task 2 --grid 9 --methods all --csv",
        "atlas --arm panda --grid 5 --methods numerical,qp --json",
        "atlas --task 2 --grid 7 --out {out}",
        "atlas --arm panda --grid 5 --methods numerical,qp --out {out}",
        "figure --task 1 --method case3 --out {out}",
        "figure --task 2 --method numerical --ellipse --out {out}",
        "figure --task 1 --compare --out {out}",
        "figure --task 1 --method qp --plots --out {out}",
        "figure --arm panda --method qp --out {out}",
    ] {
        out.push(args(extra));
    }
    out
}

/// What a command printed (or wrote to `{out}`), with its exit status and
/// standard error when it failed (a refusal is an output too).
fn output(args: &[String], scratch: &Path) -> String {
    let file = scratch.join("out.svg");
    let _ = std::fs::remove_file(&file);
    let args: Vec<String> = args
        .iter()
        .map(|a| a.replace("{out}", &file.to_string_lossy()))
        .collect();
    let run = Command::new(env!("CARGO_BIN_EXE_redundant-ik"))
        .args(&args)
        .output()
        .expect("the binary runs");
    let mut text = String::from_utf8_lossy(&run.stdout).into_owned();
    if args.iter().any(|a| a.ends_with("out.svg")) && run.status.success() {
        text = std::fs::read_to_string(&file).expect("the figure was written");
    }
    if !run.status.success() {
        text.push_str(&format!(
            "exit {:?}: {}",
            run.status.code(),
            String::from_utf8_lossy(&run.stderr)
        ));
    }
    text
}

#[test]
fn every_output_is_what_it_was_to_the_bit() {
    let scratch = std::env::temp_dir().join(format!("redundant-ik-golden-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let now: BTreeMap<String, (u64, u64)> = commands()
        .iter()
        .map(|c| {
            let text = output(c, &scratch);
            (c.join(" "), (fnv(text.bytes()), numbers_digest(&text)))
        })
        .collect();
    let _ = std::fs::remove_dir_all(&scratch);
    if std::env::var_os("GOLDEN_WRITE").is_some() {
        let mut file = String::from("# command\ttext digest\tnumbers digest (tests/golden.rs)\n");
        for (c, (t, n)) in &now {
            file.push_str(&format!("{c}\t{t:016x}\t{n:016x}\n"));
        }
        std::fs::write(FILE, file).unwrap();
        return;
    }
    let text = std::fs::read_to_string(FILE).expect("tests/data/golden.tsv");
    let was: BTreeMap<&str, (&str, &str)> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut f = l.split('\t');
            Some((f.next()?, (f.next()?, f.next()?)))
        })
        .collect();
    let mut changed = Vec::new();
    for (c, (t, n)) in &now {
        match was.get(c.as_str()) {
            None => changed.push(format!("{c}: not in {FILE}")),
            Some((wt, wn)) => {
                if *wn != format!("{n:016x}") {
                    changed.push(format!("{c}: its numbers changed"));
                } else if *wt != format!("{t:016x}") {
                    changed.push(format!("{c}: its text changed (its numbers did not)"));
                }
            }
        }
    }
    for c in was.keys().filter(|c| !now.contains_key(**c)) {
        changed.push(format!("{c}: in {FILE} but no longer run"));
    }
    assert!(
        changed.is_empty(),
        "{} of {} outputs differ from {FILE}:\n{}",
        changed.len(),
        now.len(),
        changed.join("\n")
    );
}

#[test]
fn the_numbers_digest_ignores_keys_and_order_but_not_a_bit() {
    let a = r#"{"ee": [0.1, 2.5e-3], "t": 1}"#;
    let b = r#"{"t": 1, "hand": [0.1, 2.5e-3]}"#;
    assert_eq!(numbers_digest(a), numbers_digest(b));
    assert_ne!(fnv(a.bytes()), fnv(b.bytes()));
    let c = r#"{"ee": [0.10000000000000002, 2.5e-3], "t": 1}"#;
    assert_ne!(numbers_digest(a), numbers_digest(c));
}

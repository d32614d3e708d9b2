//! Bad and hostile input through every subcommand, and bad weights files:
//! one readable error line and exit status 2.

use super::*;

#[test]
fn bad_input_is_one_error_line_and_exit_status_2() {
    let table: &[(&[&str], &str)] = &[
        (&["simulate", "--theta0", "nan,0,0"], "finite"),
        (&["simulate", "--lambda", "inf"], "lambda"),
        (&["simulate", "--dt", "0"], "dt"),
        (&["simulate", "--dt", "-0.1"], "dt"),
        (&["simulate", "--tf", "1.05"], "whole number"),
        (&["simulate", "--obstacle", "1"], "x,y or x,y,r"),
        (&["simulate", "--obstacle", "a,b"], "obstacle"),
        (&["simulate", "--obstacle", "0,0.3"], "post"),
        (&["simulate", "--radius", "-1"], "radius"),
        (&["simulate", "--feedback", "-1"], "feedback"),
        (&["simulate", "--feedback", "100"], "unstable"),
        (&["simulate", "--target", "1e9,0"], "within"),
        (&["simulate", "--task", "3"], "task 3"),
        (&["simulate", "--method", "case4"], "method"),
        (&["simulate", "--theta0", "0,1"], "3"),
        (&["figure", "--task", "1"], "required"),
        // One namespace of arms: a word that names none lists every name.
        (
            &["simulate", "--arm", "ur99"],
            "unknown arm 'ur99': the planar paper, four, five, iiwa-planar or, in space, panda, iiwa14, or a planar arm post:l1,l2,...",
        ),
        (&["train", "--net", "phi", "--arm", "ur99", "--out", "x.json"], "unknown arm 'ur99'"),
        (&["bench", "--arm", "paper"], "unknown arm in space 'paper': use panda or iiwa14"),
        (&["robot", "--urdf-of", "ur99"], "unknown arm in space 'ur99'"),
    ];
    for (args, what) in table {
        refused(args, what);
    }
}

/// Hostile input through every subcommand: NaN, infinities, 1e308, huge
/// lists, negative radii, 0 or 100 links, garbage. Each is one `error:`
/// line naming the problem, exit status 2, no panic (docs/reliability.md).
#[test]
fn hostile_input_through_every_subcommand_is_one_readable_error() {
    let hundred_links = format!("0.5:{}", vec!["0.1"; 100].join(","));
    let huge_list = vec!["0.1"; 10_000].join(",");
    let table: &[(&[&str], &str)] = &[
        // NaN and infinities, wherever a number goes.
        (&["simulate", "--lambda", "NaN"], "lambda"),
        (&["simulate", "--lambda", "-inf"], "lambda"),
        (&["simulate", "--delta", "nan"], "delta"),
        (&["simulate", "--target", "NaN,0.2"], "target"),
        (&["simulate", "--target", "0.6,inf"], "target"),
        (&["simulate", "--obstacle", "nan,0.5"], "obstacle"),
        (&["simulate", "--theta0", "0,inf,0"], "theta"),
        (&["simulate", "--tf", "inf"], "tf"),
        (&["simulate", "--dt", "nan"], "dt"),
        (&["atlas", "--region", "0,1,0,inf"], "finite"),
        (&["bench", "--batch-ms", "inf"], "batch"),
        (&["eval", "--feedback", "nan"], "feedback"),
        (
            &["figure", "--lambda", "nan", "--out", "/dev/null"],
            "lambda",
        ),
        // Finite but absurd.
        (&["simulate", "--lambda", "1e308"], "lambda"),
        (&["simulate", "--delta", "1e308"], "delta"),
        (&["simulate", "--target", "1e308,0"], "within"),
        (&["simulate", "--obstacle", "0.5,1e308"], "within"),
        (&["simulate", "--theta0", "1e308,1e308,0"], "rad"),
        (&["simulate", "--tf", "1e308"], "steps"),
        (&["simulate", "--dt", "1e-300"], "steps"),
        (&["simulate", "--feedback", "1e308"], "unstable"),
        (&["simulate", "--arm", "0.5:1e308,1"], "link length l1"),
        (&["simulate", "--arm", "1e308:1,1"], "post"),
        (&["atlas", "--grid", "18446744073709551616"], "grid"),
        (&["atlas", "--region", "-1e308,1e308,0,1"], "within"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--samples",
                "1e9",
                "--out",
                "/dev/null",
            ],
            "samples",
        ),
        (
            &[
                "train",
                "--net",
                "phi",
                "--epochs",
                "0",
                "--out",
                "/dev/null",
            ],
            "epoch",
        ),
        (&["eval", "--samples", "0"], "samples"),
        (&["bench", "--batch-ms", "1e308"], "batch"),
        // Negative radii and lengths.
        (&["simulate", "--radius", "-0.05"], "radius"),
        (&["simulate", "--obstacle", "0.5,0.5,-0.05"], "radius"),
        (&["atlas", "--radius", "-1"], "radius"),
        (
            &["simulate", "--arm", "0.5:0.6,-0.85,0.6"],
            "link length l2",
        ),
        (
            &["train", "--net", "v", "--noise=-1", "--out", "/dev/null"],
            "noise",
        ),
        // 0, 1 or 100 links; huge lists.
        (&["simulate", "--arm", "0.5:"], "not a finite number"),
        (&["simulate", "--arm", "0.5:0.6"], "link"),
        (&["simulate", "--arm", &hundred_links], "link"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--arm",
                &hundred_links,
                "--out",
                "/dev/null",
            ],
            "link",
        ),
        (&["simulate", "--theta0", &huge_list], "10000"),
        (&["simulate", "--target", &huge_list], "x,y"),
        (&["atlas", "--region", &huge_list], "four numbers"),
        (
            &[
                "train",
                "--net",
                "phi",
                "--hidden",
                &huge_list,
                "--out",
                "/dev/null",
            ],
            "hidden",
        ),
        // Garbage.
        (&["simulate", "--lambda", "four"], "lambda"),
        (&["simulate", "--target", "x,y"], "target"),
        (&["simulate", "--method", "\u{1F4A5}"], "method"),
        (&["simulate", "--task=-1"], "task"),
        (&["simulate", "--arm", "::"], "arm"),
        (&["atlas", "--methods", ",,,"], "method"),
        (&["train", "--net", "both", "--out", "/dev/null"], "net"),
        (&["simulate", "--phi-variant", "sideways"], "phi-variant"),
        (&["simulate", "--bogus"], "unexpected argument"),
    ];
    for (args, what) in table {
        refused(args, what);
    }
}

/// Weights files that are huge, truncated, hold NaN or another arm's
/// networks, or are not text: refused with the reason, through every
/// subcommand that reads them.
#[test]
fn hostile_weights_files_are_refused_with_the_reason() {
    let phi = std::fs::read_to_string("weights/phi-equivariant.json").unwrap();
    let v = std::fs::read_to_string("weights/v-plain.json").unwrap();
    let write = |name: &str, bytes: &[u8]| {
        let p = scratch(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_owned()
    };
    let huge = write("huge.json", &vec![b' '; (8 << 20) + 1]);
    let truncated = write("truncated.json", &phi.as_bytes()[..phi.len() / 2]);
    let first_weight = phi.find("\"weights\": [").unwrap() + "\"weights\": [".len();
    let nan = write(
        "nan.json",
        format!("{}NaN,{}", &phi[..first_weight], &phi[first_weight..]).as_bytes(),
    );
    let overflow = write(
        "overflow.json",
        format!("{}1e999,{}", &phi[..first_weight], &phi[first_weight..]).as_bytes(),
    );
    let binary = write("binary.json", &[0xff, 0xfe, 0x00, 0x01, 0x80]);
    let mut other: Value = serde_json::from_str(&v).unwrap();
    other["arm"]["links"] = serde_json::json!([0.6, 0.85, 0.6, 0.4]);
    let other = write("other-arm.json", other.to_string().as_bytes());
    let v = write("v.json", v.as_bytes());
    let cases: &[(&str, &str)] = &[
        (&huge, "at most 8 mb"),
        (&truncated, "not a valid weights file"),
        (&nan, "not a valid weights file"),
        (&overflow, "not a valid weights file"),
        (&binary, "cannot read"),
    ];
    for (file, what) in cases {
        refused(
            &[
                "simulate",
                "--method",
                "case3",
                "--phi-weights",
                file,
                "--v-weights",
                &v,
            ],
            what,
        );
        refused(&["eval", "--phi", file, "--v", &v], what);
        refused(
            &[
                "atlas",
                "--grid",
                "2",
                "--methods",
                "case1",
                "--phi-weights",
                file,
                "--v-weights",
                &v,
            ],
            what,
        );
    }
    refused(
        &["simulate", "--method", "case2", "--v-weights", &other],
        "arm",
    );
}

#[test]
fn a_corrupt_or_mismatched_weights_file_is_refused_with_the_reason() {
    let bad = scratch("bad.json");
    std::fs::write(&bad, "{\"format\": 12").unwrap();
    let bad = bad.to_str().unwrap();
    refused(
        &["simulate", "--method", "case1", "--phi-weights", bad],
        "weights",
    );
    refused(
        &[
            "simulate",
            "--method",
            "case1",
            "--phi-weights",
            "weights/v-plain.json",
        ],
        "phi",
    );
    refused(
        &[
            "simulate",
            "--method",
            "case2",
            "--v-weights",
            "no/such/file.json",
        ],
        "cannot read",
    );
}

//! The networks of an arm in space on the command line: `--networks
//! panda-reach`, `train --arm panda`, `eval --arm panda`, own files.

use super::{ok, refused, scratch};

#[test]
fn the_learned_methods_train_evaluate_and_run_for_the_panda() {
    // Case 3 with the shipped panda-reach set (its default for the Panda),
    // refined and closed-loop, reaches the target.
    let text = ok(&[
        "simulate",
        "--arm",
        "panda",
        "--method",
        "case3",
        "--refine",
        "2",
        "--feedback",
        "1",
    ]);
    let err: f64 = text
        .lines()
        .find(|l| l.starts_with("final hand error"))
        .and_then(|l| l.split_whitespace().nth(3))
        .and_then(|x| x.parse().ok())
        .unwrap();
    assert!(err < 1e-3, "{text}");
    let text = ok(&["eval", "--arm", "panda", "--samples", "50"]);
    assert!(
        text.contains("Phi [12, 96, 96, 21]") && text.contains("Case 3"),
        "{text}"
    );
    // A short training writes a file the planner takes back.
    let (phi, v) = (scratch("space-phi.json"), scratch("space-v.json"));
    for (net, out) in [("phi", &phi), ("v", &v)] {
        ok(&[
            "train",
            "--arm",
            "panda",
            "--net",
            net,
            "--samples",
            "200",
            "--epochs",
            "2",
            "--hidden",
            "8",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    ok(&[
        "simulate",
        "--arm",
        "panda",
        "--method",
        "case2",
        "--phi-weights",
        phi.to_str().unwrap(),
        "--v-weights",
        v.to_str().unwrap(),
    ]);
    refused(
        &[
            "train",
            "--arm",
            "panda",
            "--net",
            "phi",
            "--recipe",
            "paper",
            "--out",
            "/dev/null",
        ],
        "whole-reach recipe in space",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "iiwa14",
            "--method",
            "case2",
            "--phi-weights",
            phi.to_str().unwrap(),
            "--v-weights",
            v.to_str().unwrap(),
        ],
        "trained for the arm 'panda'",
    );
}

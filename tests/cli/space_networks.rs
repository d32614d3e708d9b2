//! The networks of an arm in space on the command line: `--networks
//! panda-reach`, `train --arm panda`, `eval --arm panda`, own files.

use super::{cli, ok, refused, scratch, stderr};

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

#[test]
fn a_robot_read_from_urdf_trains_its_own_networks_and_runs_them() {
    let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5e.urdf");
    let (phi, v) = (scratch("ur5e-phi.json"), scratch("ur5e-v.json"));
    for (net, out) in [("phi", &phi), ("v", &v)] {
        let text = ok(&[
            "train",
            "--urdf",
            urdf,
            "--net",
            net,
            "--samples",
            "300",
            "--epochs",
            "3",
            "--hidden",
            "8",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(text.contains("network for ur5e"), "{text}");
    }
    let (phi, v) = (phi.to_str().unwrap(), v.to_str().unwrap());
    // The robot's own scene runs Case 2 with them.
    let text = ok(&[
        "simulate",
        "--urdf",
        urdf,
        "--method",
        "case2",
        "--phi-weights",
        phi,
        "--v-weights",
        v,
    ]);
    assert!(text.contains("final hand error"), "{text}");
    // eval gives their accuracy and the task past a sphere of 0.05 of the
    // UR5e's reach, from the start given.
    let text = ok(&[
        "eval",
        "--urdf",
        urdf,
        "--phi",
        phi,
        "--v",
        v,
        "--samples",
        "40",
        "--theta0=0,-1.2,1.5,-1.5,-1.5,0",
    ]);
    assert!(
        text.contains("Networks for ur5e")
            && text.contains("Phi [10, 8, 18]")
            && text.contains("of radius 0.066 m")
            && text.contains("Case 3"),
        "{text}"
    );
    // No set is shipped for it; the Panda's does not fit it, nor its
    // networks the Panda.
    refused(
        &["eval", "--urdf", urdf, "--samples", "10"],
        "no networks are shipped for ur5e",
    );
    // The Panda read from its URDF is not the preset's chain of rows: its
    // shipped networks do not serve it, and the message says why.
    let panda = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/panda.urdf");
    refused(
        &["eval", "--urdf", panda, "--samples", "10"],
        "not for this panda read from urdf",
    );
    refused(
        &[
            "simulate",
            "--arm",
            "panda",
            "--method",
            "case2",
            "--phi-weights",
            phi,
            "--v-weights",
            v,
        ],
        "trained for another chain",
    );
}

#[test]
fn training_refuses_what_the_networks_cannot_serve() {
    let slider = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/urdf/slider_arm.urdf"
    );
    let ur5e = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/ur5e.urdf");
    // The reader's warnings on its links come first, then the refusal.
    let out = cli(&[
        "train",
        "--urdf",
        slider,
        "--tip",
        "tool",
        "--net",
        "phi",
        "--out",
        "/dev/null",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.lines()
            .last()
            .is_some_and(|l| l.starts_with("error:") && l.contains("first joint slides")),
        "{err}"
    );
    refused(
        &[
            "train",
            "--tip",
            "tool",
            "--net",
            "phi",
            "--out",
            "/dev/null",
        ],
        "--tip goes with --urdf file",
    );
    refused(
        &[
            "train",
            "--urdf",
            ur5e,
            "--srdf",
            ur5e,
            "--net",
            "v",
            "--out",
            "/dev/null",
        ],
        "self-collision does not enter",
    );
    refused(
        &[
            "eval", "--urdf", ur5e, "--theta0", "0,1", "--phi", ur5e, "--v", ur5e,
        ],
        "--theta0",
    );
}

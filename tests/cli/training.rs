//! `train`: weights files for any arm that `simulate` accepts, and the
//! reach recipe and network set.

use super::*;

#[test]
fn train_writes_a_weights_file_that_simulate_accepts() {
    let out = scratch("tiny-phi.json");
    let path = out.to_str().unwrap();
    let text = ok(&[
        "train",
        "--net",
        "phi",
        "--variant",
        "equivariant",
        "--samples",
        "200",
        "--epochs",
        "5",
        "--hidden",
        "8",
        "--quiet",
        "--out",
        path,
    ]);
    assert!(
        text.to_lowercase().contains("test"),
        "reports its test error: {text}"
    );
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(file["net"], "phi");
    // A barely trained net still runs to the end without a panic or NaN; the
    // summary reports what it did.
    let run = json(&[
        "simulate",
        "--method",
        "case1",
        "--phi-weights",
        path,
        "--json",
    ]);
    assert!(run["summary"]["final_error"]
        .as_f64()
        .is_some_and(f64::is_finite));
}

#[test]
fn train_and_simulate_take_any_arm() {
    let arm = "0.5:0.6,0.85,0.6,0.4";
    let phi = scratch("phi-4.json");
    let v = scratch("v-4.json");
    for (net, variant, out) in [("phi", "equivariant", &phi), ("v", "plain", &v)] {
        ok(&[
            "train",
            "--arm",
            arm,
            "--net",
            net,
            "--variant",
            variant,
            "--samples",
            "200",
            "--epochs",
            "3",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&phi).unwrap()).unwrap();
    assert_eq!(file["arm"]["links"].as_array().unwrap().len(), 4);
    assert_eq!(file["training"]["sampling"]["random_tasks"], 60);
    // The numerical route runs on the arm at once, from its start pose, with
    // obstacles of their own radii.
    let s = json(&[
        "simulate",
        "--arm",
        arm,
        "--method",
        "numerical",
        "--obstacle",
        "0.5,0.5,0.08",
        "--obstacle",
        "-0.4,1.2",
        "--json",
    ]);
    assert_eq!(s["steps"][0]["theta"].as_array().unwrap().len(), 4);
    assert_eq!(s["summary"]["reached"], true);
    // Case 3 with the networks trained for it, and an explicit start pose.
    let s = json(&[
        "simulate",
        "--arm",
        arm,
        "--method",
        "case3",
        "--theta0",
        "0.2,1.4,-0.5,-0.5",
        "--phi-weights",
        phi.to_str().unwrap(),
        "--v-weights",
        v.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(s["steps"][0]["theta"][1], 1.4);
    // Networks for another arm, a start pose of the wrong length, bad arms.
    refused(&["simulate", "--arm", arm, "--method", "case3"], "arm");
    refused(
        &["simulate", "--arm", arm, "--theta0", "0.1,0.2,0.3"],
        "theta",
    );
    refused(&["simulate", "--arm", "0.5:0.6"], "link");
    refused(&["simulate", "--arm", "0.5,0.6,0.6"], "post:l1");
    refused(&["simulate", "--arm", "0.5:0.6,x"], "not a finite number");
    refused(&["simulate", "--arm", "-1:0.6,0.6"], "post");
    refused(&["simulate", "--obstacle", "0.5,0.5,-0.1"], "radius");
    refused(&["simulate", "--obstacle", "0.5,0.5,0.1,3"], "x,y,r");
    refused(&["train", "--arm", "0.5:0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6,0.6", "--net", "phi", "--out", "/dev/null"], "link");
}

#[test]
fn the_reach_recipe_and_network_set_through_the_command_line() {
    // `train --recipe reach` writes angle features and the smoothed sign.
    let out = scratch("tiny-reach-v.json");
    let path = out.to_str().unwrap();
    let text = ok(&[
        "train",
        "--net",
        "v",
        "--recipe",
        "reach",
        "--samples",
        "200",
        "--epochs",
        "3",
        "--hidden",
        "6",
        "--quiet",
        "--out",
        path,
    ]);
    assert!(
        text.contains("recipe reach") && text.contains("encoding angles"),
        "{text}"
    );
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(file["encoding"], "angles");
    assert_eq!(file["variant"], "equivariant");
    assert_eq!(file["training"]["sampling"]["sign_smoothing"], 0.1);
    // The shipped reach set runs Case 3 with refinement and feedback, and
    // the refinement changes the run (it is applied).
    let run = |refine: &str| {
        json(&[
            "simulate",
            "--method",
            "case3",
            "--networks",
            "reach",
            "--refine",
            refine,
            "--feedback",
            "1",
            "--json",
        ])
    };
    let (plain, refined) = (run("0"), run("2"));
    assert_eq!(refined["scene"]["params"]["refine"], 2.0);
    assert!(refined["summary"]["final_error"].as_f64().unwrap() < 5e-3);
    assert_ne!(plain["summary"], refined["summary"]);
    // A figure of the refined run says so in its caption.
    let fig = scratch("refined-case3.svg");
    ok(&[
        "figure",
        "--method",
        "case3",
        "--networks",
        "reach",
        "--refine",
        "2",
        "--out",
        fig.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&fig).unwrap();
    assert!(
        svg.contains("Φ refined by 2 Newton-Schulz steps"),
        "caption of {fig:?}"
    );
    // The exact route is the same with either set (it runs no network).
    let numerical = |set: &str| {
        json(&[
            "simulate",
            "--method",
            "numerical",
            "--networks",
            set,
            "--json",
        ])["summary"]
            .clone()
    };
    assert_eq!(numerical("paper"), numerical("reach"));
    // `--optimiser adam` trains by Adam and records its options; Adam's
    // settings without it are refused rather than ignored.
    let adam_out = scratch("tiny-adam-phi.json");
    let adam_path = adam_out.to_str().unwrap();
    ok(&[
        "train",
        "--net",
        "phi",
        "--samples",
        "200",
        "--epochs",
        "2",
        "--hidden",
        "6",
        "--optimiser",
        "adam",
        "--batch",
        "32",
        "--learning-rate",
        "0.01",
        "--quiet",
        "--out",
        adam_path,
    ]);
    let file: Value = serde_json::from_str(&std::fs::read_to_string(&adam_out).unwrap()).unwrap();
    assert_eq!(file["training"]["adam"]["batch"], 32);
    assert_eq!(file["training"]["adam"]["max_epochs"], 2);
    assert_eq!(file["nets"][0]["report"]["epochs"].as_u64(), Some(2));
    refused(
        &[
            "train",
            "--net",
            "phi",
            "--batch",
            "32",
            "--out",
            "/dev/null",
        ],
        "--optimiser adam",
    );
    // A network too wide for Levenberg-Marquardt's J^T J is refused with
    // the way out, not an allocation that kills the process.
    let wide = "train --net phi --samples 100 --hidden 96,96 --optimiser lm --out /dev/null";
    refused(&wide.split(' ').collect::<Vec<_>>(), "--optimiser adam");
    refused(&["simulate", "--networks", "nope"], "networks");
    refused(&["simulate", "--refine", "1.5"], "refine");
    refused(&["simulate", "--refine", "9"], "refine");
    refused(&["simulate", "--sign-smoothing", "-1"], "smoothing");
    refused(
        &[
            "simulate",
            "--method",
            "case1",
            "--networks",
            "reach",
            "--phi-variant",
            "plain",
        ],
        "phi-variant",
    );
    refused(
        &["train", "--net", "v", "--recipe", "both", "--out", path],
        "recipe",
    );
    // eval of the reach set.
    let text = ok(&[
        "eval",
        "--networks",
        "reach",
        "--refine",
        "2",
        "--feedback",
        "1",
        "--samples",
        "200",
    ]);
    assert!(text.contains("feedback K = 1, refine 2"), "{text}");
}

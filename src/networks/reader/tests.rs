//! The page's reader of weights files against serde's derived one.

use super::by_hand::read;
// The derived readers exist where the tool's or the workers' features are on.
#[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
use {super::by_hand::unread_report, crate::networks::WeightsFile};

/// The derived reader's file with what the page skips replaced by the
/// page reader's placeholders.
#[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
fn as_the_page_reads_it(mut file: WeightsFile) -> WeightsFile {
    file.training.options = crate::nn::lm::LmOptions::default();
    file.training.adam = None;
    for net in &mut file.nets {
        net.report = unread_report();
    }
    file
}

fn shipped() -> Vec<(String, String)> {
    let mut files: Vec<_> = std::fs::read_dir("weights")
        .expect("the weights folder")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("readable");
            (p.display().to_string(), text)
        })
        // The planar files (the shipped ones are of version 1).
        .filter(|(_, text)| text.contains(crate::networks::file::FORMAT_1))
        .collect();
    files.sort();
    assert!(files.len() >= 6, "the shipped weights files");
    files
}

/// Every shipped weights file reads to the same networks, arm, range and
/// sampling with the page's reader as with the derived one.
#[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
#[test]
fn the_page_reads_every_shipped_file_as_the_tool_does() {
    for (name, text) in shipped() {
        let derived: WeightsFile = serde_json::from_str(&text).expect(&name);
        let page = read(&text).expect(&name);
        assert_eq!(page, as_the_page_reads_it(derived), "{name}");
    }
}

/// A file with every optional field set and the older names, written
/// by the derived writer, reads the same with both readers.
#[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
#[test]
fn every_optional_field_and_older_name_reads_as_the_tool_reads_it() {
    let (_, text) = &shipped()[0];
    let mut value: serde_json::Value = serde_json::from_str(text).expect("JSON");
    let s = &mut value["training"]["sampling"];
    s["random_tasks"] = 7.into();
    s["obstacle_spread"] = 0.05.into();
    s["whole_torus"] = true.into();
    s["sign_smoothing"] = 1e-4.into();
    let methods = s["methods"].take();
    s.as_object_mut().expect("an object").remove("methods");
    s["modes"] = methods;
    value["training"]["seconds"] = 12.5.into();
    value["encoding"] = "raw".into();
    value["arm"]["joint_limits"] = serde_json::json!([[-3, 3], [-2.5, 2.5], [-2, 2]]);
    value["arm"]["rate_limits"] = serde_json::json!([1, 2, 3.5]);
    let text = value.to_string();
    let derived: WeightsFile = serde_json::from_str(&text).expect("the tool reads it");
    let page = read(&text).expect("the page reads it");
    assert_eq!(page, as_the_page_reads_it(derived));
    assert!(page.arm.joint_limits().is_some());
    assert!(page.training.sampling.whole_torus);
}

/// What the derived readers refuse, the page's refuses too, each with a
/// message that names the field.
#[test]
fn what_the_tool_refuses_the_page_refuses_and_says_where() {
    let (_, text) = &shipped()[0];
    let base: serde_json::Value = serde_json::from_str(text).expect("JSON");
    type Change = Box<dyn Fn(&mut serde_json::Value)>;
    let cases: Vec<(&str, Change)> = vec![
        (
            "missing field `nets`",
            Box::new(|v| drop(v.as_object_mut().unwrap().remove("nets"))),
        ),
        (
            "unknown field `colour`",
            Box::new(|v| v["colour"] = "red".into()),
        ),
        (
            "sampling: Sampling: unknown field `extra`",
            Box::new(|v| v["training"]["sampling"]["extra"] = 1.into()),
        ),
        (
            "net: unknown variant `w`",
            Box::new(|v| v["net"] = "w".into()),
        ),
        (
            "variant: unknown variant",
            Box::new(|v| v["variant"] = "diagonal".into()),
        ),
        (
            "samples: invalid type: a floating point number",
            Box::new(|v| v["training"]["samples"] = 2.5.into()),
        ),
        (
            "samples: invalid type: an integer",
            Box::new(|v| v["training"]["samples"] = (-1).into()),
        ),
        (
            "obstacle_min: invalid length 3",
            Box::new(|v| v["training"]["sampling"]["obstacle_min"] = serde_json::json!([0, 1, 2])),
        ),
        (
            "link length",
            Box::new(|v| v["arm"]["links"] = serde_json::json!([0.6, -1, 0.6])),
        ),
        (
            "missing field `report`",
            Box::new(|v| drop(v["nets"][0].as_object_mut().unwrap().remove("report"))),
        ),
        (
            "missing field `options`",
            Box::new(|v| drop(v["training"].as_object_mut().unwrap().remove("options"))),
        ),
        (
            "methods: [0]: unknown method",
            Box::new(|v| v["training"]["sampling"]["methods"] = serde_json::json!(["flying"])),
        ),
        (
            "weights: [0]: invalid type: a string",
            Box::new(|v| v["nets"][0]["mlp"]["layers"][0]["weights"][0] = "x".into()),
        ),
    ];
    for (message, change) in cases {
        let mut v = base.clone();
        change(&mut v);
        let text = v.to_string();
        let page = read(&text).expect_err(message);
        assert!(page.contains(message), "{message}: got '{page}'");
        #[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
        assert!(
            serde_json::from_str::<WeightsFile>(&text).is_err(),
            "the tool refuses {message}"
        );
    }
    let repeated = text_with_repeated_field(text);
    assert!(read(&repeated)
        .expect_err("repeated")
        .contains("duplicate field `format`"));
    for broken in [
        "",
        "[",
        "{\"format\": ",
        "\u{0}\u{ff}garbage",
        "null",
        "[1, 2]",
    ] {
        assert!(read(broken).is_err(), "{broken:?} is refused");
    }
}

fn text_with_repeated_field(text: &str) -> String {
    text.replacen('{', "{\"format\": \"x\", ", 1)
}

/// A JSON tree deeper than serde_json's recursion limit is refused, not
/// a stack overflow.
#[test]
fn a_deep_tree_is_refused() {
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    assert!(read(&deep).is_err());
}

/// Every shipped spatial weights file (version 1) reads to the same file
/// with the page's reader as with the derived one (the optimiser's
/// options, which the page does not read, at their defaults), and so does
/// the same file written in this version's layout, the chain whole in it.
#[cfg(any(feature = "worker", feature = "cli", feature = "eval"))]
#[test]
fn the_page_reads_the_spatial_weights_files_as_the_derived_reader_does() {
    use crate::networks::space::{SpaceWeightsFile, SpaceWeightsFile1, SPACE_FORMAT_1};
    let unread = |mut f: SpaceWeightsFile| {
        f.training.adam = crate::nn::adam::AdamOptions::default();
        for net in &mut f.nets {
            net.report = super::by_hand::unread_report();
        }
        f
    };
    let mut n = 0;
    for entry in std::fs::read_dir("weights").expect("the weights folder") {
        let path = entry.expect("an entry").path();
        let text = std::fs::read_to_string(&path).expect("readable");
        if !text.contains(SPACE_FORMAT_1) {
            continue;
        }
        let old: SpaceWeightsFile1 = serde_json::from_str(&text).expect("the derived reader");
        let derived = old.into_current().expect("a chain");
        assert_eq!(derived.format, crate::networks::FORMAT);
        assert!(crate::space::SpacePreset::of(&derived.arm).is_some_and(|p| p.key == "panda"));
        let by_hand = super::space::read(&text).expect("the page's reader");
        assert_eq!(by_hand, unread(derived.clone()), "{}", path.display());
        // This version's file, written and read back by both readers.
        let now = derived.to_json().unwrap();
        let again: SpaceWeightsFile = serde_json::from_str(&now).expect("the derived reader");
        assert_eq!(again, derived);
        assert_eq!(super::space::read(&now).unwrap(), unread(derived));
        // A field too many, or one missing, is refused as the derived reader refuses it.
        for text in [&text, &now] {
            let extra = text.replacen('{', "{\"extra\": 1, ", 1);
            assert!(super::space::read(&extra).is_err());
            let missing = text.replacen("\"tool_version\"", "\"tool_versio\"", 1);
            assert!(super::space::read(&missing).is_err());
        }
        assert!(serde_json::from_str::<SpaceWeightsFile1>(&text.replacen(
            '{',
            "{\"extra\": 1, ",
            1
        ))
        .is_err());
        assert!(
            serde_json::from_str::<SpaceWeightsFile>(&now.replacen('{', "{\"extra\": 1, ", 1))
                .is_err()
        );
        n += 1;
    }
    assert_eq!(n, 2, "the Panda's two files");
}

/// A chain read from URDF, with a tip's fixed rotation and self pairs, as
/// the workers' module hands it to the page: the page's reader by hand
/// reads it back equal, and refuses what the derived reader refuses.
#[test]
fn a_urdf_chain_reads_back_by_hand_with_its_flange_rotation_and_self_pairs() {
    use crate::urdf::{volume, Urdf, UrdfChain};
    let text = std::fs::read_to_string("robots/ur5e.urdf").expect("the UR5e's URDF");
    let urdf = Urdf::parse(&text).expect("it reads");
    let uc = UrdfChain::new(&urdf, None, None).expect("one chain");
    let (volumes, _) = volume::volumes(&urdf, &uc, &|_: &str| None, 0.05);
    let chain = uc.to_chain(&volumes, None).expect("a chain");
    let chain = chain
        .with_flange_rotation([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
        .expect("a rotation");
    let zero = vec![0.0; chain.dof()];
    let chain = chain
        .with_self_collision(&[], &[&zero])
        .expect("self pairs");
    assert!(!chain.self_pairs().is_empty());
    let json = serde_json::to_string(&chain).unwrap();
    assert!(json.contains("flange_rotation") && json.contains("self_pairs"));
    assert_eq!(
        super::space::read_chain(&json).expect("read by hand"),
        chain
    );
    assert!(super::space::read_chain(&json.replacen('{', "{\"extra\": 1, ", 1)).is_err());
    assert!(super::space::read_chain(&json.replacen("\"radius\"", "\"radios\"", 1)).is_err());
}

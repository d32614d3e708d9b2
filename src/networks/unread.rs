//! What the page's module (feature `page` without `worker`, `cli` or `eval`) does not
//! read of a weights file: the trainer's options and reports. It uses a
//! file's networks, input ranges and sampling (the obstacle region), never
//! how they were trained, and keeps the file's text for the workers, which
//! read all of it. Skipped as any JSON value (`IgnoredAny`), they take
//! placeholders: their readers were about 9 KB of the module (`twiggy`).

use serde::de::{Deserialize, Deserializer, IgnoredAny};

use crate::nn::adam::AdamOptions;
use crate::nn::lm::{LmOptions, StopReason, TrainReport};

/// What stands in for a value the page does not read.
pub trait Placeholder {
    fn placeholder() -> Self;
}

impl Placeholder for LmOptions {
    fn placeholder() -> Self {
        LmOptions::default()
    }
}

impl Placeholder for Option<AdamOptions> {
    fn placeholder() -> Self {
        None
    }
}

impl Placeholder for TrainReport {
    fn placeholder() -> Self {
        TrainReport {
            epochs: 0,
            best_epoch: 0,
            stop: StopReason::MaxEpochs,
            train_mse: 0.0,
            val_mse: 0.0,
            test_mse: 0.0,
            split: [0; 3],
        }
    }
}

/// Any JSON value, skipped.
pub fn skip<'de, D: Deserializer<'de>, T: Placeholder>(d: D) -> Result<T, D::Error> {
    IgnoredAny::deserialize(d)?;
    Ok(T::placeholder())
}

#[cfg(test)]
mod tests {
    use crate::networks::WeightsFile;

    /// A shipped weights file reads in the page's build, its networks and
    /// sampling kept, its training options and reports skipped as any JSON
    /// value (the workers' build refuses these; the page uses neither).
    #[test]
    fn a_weights_file_reads_without_its_training_options_and_reports() {
        let text = std::fs::read_to_string("weights/v-plain.json").expect("the shipped v file");
        let file = WeightsFile::from_json(&text).expect("it reads");
        assert!(file.training.adam.is_none());
        let s = &file.training.sampling;
        assert!(
            s.obstacle_max[0] > s.obstacle_min[0],
            "the sampling is read"
        );
        let mut odd: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        odd["training"]["options"] = serde_json::json!([1, { "x": null }]);
        odd["nets"][0]["report"] = serde_json::json!("anything");
        let read = WeightsFile::from_json(&odd.to_string()).expect("skipped");
        assert_eq!(
            read.nets[0].mlp, file.nets[0].mlp,
            "the network is the same"
        );
    }
}

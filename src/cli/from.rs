//! `--from`: the run file a command replays, read once for every arm
//! (a planar arm's, a chain's for the hand's position or its pose), with
//! no scene option beside it.

use redundant_ik::export::{self, Recorded, RunFile};

use super::simulate::SceneArgs;

impl SceneArgs {
    /// The text of `--from`'s file (at most a run file's size), if given.
    pub fn run_text(&self) -> Result<Option<String>, String> {
        let Some(path) = &self.from else {
            return Ok(None);
        };
        super::read_at_most(path, export::MAX_RUN_FILE_BYTES, "a run file").map(Some)
    }

    /// The run file of `--from`, read and checked, if given.
    pub fn run_file(&self) -> Result<Option<RunFile>, String> {
        self.run_file_of(|_| true)
    }

    /// The run file of `--from` of an arm `A` whose hand has `M`
    /// coordinates, read and checked, if given and if `kind` says its text
    /// is one (`None` otherwise); no scene option may go with it.
    pub fn run_file_of<A: Recorded<M>, const M: usize>(
        &self,
        kind: fn(&str) -> bool,
    ) -> Result<Option<RunFile<A, M>>, String>
    where
        A::Scene: serde::Serialize + serde::de::DeserializeOwned,
        [f64; M]: serde::Serialize + serde::de::DeserializeOwned,
    {
        let (Some(path), Some(text)) = (&self.from, self.run_text()?) else {
            return Ok(None);
        };
        if !kind(&text) {
            return Ok(None);
        }
        let run =
            RunFile::<A, M>::from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        // The file is the whole scene: an option beside it would be ignored.
        if let Some(flag) = self.beside_from().first() {
            return Err(format!(
                "--from gives the whole scene; {flag} cannot change it"
            ));
        }
        Ok(Some(run))
    }
}

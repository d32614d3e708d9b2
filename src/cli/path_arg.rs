//! `--path` on the command line: one text read as a planar path and as a
//! path in space, the arm's kind choosing when the scene is built.

use redundant_ik::scene::{Path, SpacePath};

/// `--path` as given, read both ways: as a planar path (`line`,
/// `circle:CX,CY[,LAPS]`, `points:X,Y;X,Y;...`) and as a path in space
/// (`circle:CX,CY,CZ,NX,NY,NZ[,LAPS]`, `points:X,Y,Z;...`); the arm's kind
/// picks one when the scene is built (`--arm` may come after `--path`).
#[derive(Debug, Clone)]
pub struct PathArg {
    /// The text given.
    pub text: String,
    /// The planar path, or why the text is not one.
    pub planar: Result<Path, String>,
    /// The path in space, or why the text is not one.
    pub space: Result<SpacePath, String>,
}

impl PathArg {
    /// The planar path, or a refusal that names a path in space as one.
    pub fn planar(&self) -> Result<Path, String> {
        self.planar.clone().map_err(|e| match &self.space {
            Ok(_) => format!(
                "--path {}: a path in space (for --arm panda or iiwa14); a planar arm takes line, circle:CX,CY[,LAPS] or points:X,Y;X,Y;...",
                self.text
            ),
            Err(_) => e,
        })
    }
}

/// What an [`redundant_ik::Error::Syntax`] expected, else its message.
fn expected(e: redundant_ik::Error) -> String {
    match e {
        redundant_ik::Error::Syntax { expected, .. } => expected,
        other => other.to_string(),
    }
}

/// Parses `--path` (the core's syntaxes, [`PathArg`]): refused here when
/// it is neither a planar path nor one in space.
pub fn parse_path(s: &str) -> Result<PathArg, String> {
    let planar = s.parse::<Path>();
    let space = s.parse::<SpacePath>();
    match (planar, space) {
        (Err(p), Err(q)) => Err(format!("{p} (for an arm in space: {})", expected(q))),
        (planar, space) => Ok(PathArg {
            text: s.to_string(),
            planar: planar.map_err(|e| e.to_string()),
            space: space.map_err(|e| e.to_string()),
        }),
    }
}

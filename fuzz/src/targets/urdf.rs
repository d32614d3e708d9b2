//! The `urdf` target.

use redundant_ik::urdf::volume;
use redundant_ik::urdf::{Urdf, UrdfChain};

/// A URDF from arbitrary bytes, as `redundant-ik robot FILE` and the page's
/// "Open robot..." read one: parse it, take the chain to its one leaf
/// (and, where there are several, to each link named in the file), make
/// its volumes. Nothing may panic, a chain has one joint at least and at
/// most the most a chain may have, and every volume is finite.
pub fn urdf(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let Ok(urdf) = Urdf::parse(&text) else {
        return;
    };
    let tips: Vec<Option<&str>> = std::iter::once(None)
        .chain(urdf.links.iter().take(8).map(|l| Some(l.name.as_str())))
        .collect();
    for tip in tips {
        let Ok(chain) = UrdfChain::new(&urdf, None, tip) else {
            continue;
        };
        assert!((1..=redundant_ik::urdf::MAX_CHAIN_JOINTS).contains(&chain.dof()));
        for j in &chain.joints {
            let n: f64 = j.axis.iter().map(|x| x * x).sum();
            assert!((n - 1.0).abs() < 1e-9, "a unit axis");
            if let Some([lo, hi]) = j.limits {
                assert!(lo <= hi);
            }
        }
        let (volumes, _) = volume::volumes(&urdf, &chain, &|_| None, 0.05);
        for v in volumes {
            let finite = v.a.iter().chain(&v.b).all(|x| x.is_finite());
            assert!(
                finite && v.radius.is_finite() && v.radius >= 0.0,
                "a finite volume"
            );
        }
    }
}

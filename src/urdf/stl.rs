//! The vertices of an STL mesh, binary or ASCII: what a link's volume is
//! fitted around ([`super::volume`]). Only the vertices are read (the
//! normals are passed over), each checked finite; a file that is neither
//! kind, cut short, or larger than [`MAX_STL_BYTES`] is refused.

use crate::error::{Error, Result};

/// Largest mesh file read (bytes).
pub const MAX_STL_BYTES: usize = 64 << 20;

/// The vertices of an STL file (three per triangle, repeats kept).
pub fn vertices(bytes: &[u8]) -> Result<Vec<[f64; 3]>> {
    let refuse = |why: String| Error::Urdf(format!("mesh: {why}"));
    if bytes.len() > MAX_STL_BYTES {
        return Err(refuse(format!(
            "{} bytes, more than the {MAX_STL_BYTES} a mesh may have",
            bytes.len()
        )));
    }
    // A binary file is 84 bytes and 50 a triangle; an ASCII one starts
    // with `solid` (some binary files do too, so the size decides first).
    if bytes.len() >= 84 {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if count.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len()) {
            return binary(bytes, count).map_err(refuse);
        }
    }
    if bytes.trim_ascii_start().starts_with(b"solid") {
        return ascii(bytes).map_err(refuse);
    }
    Err(refuse(
        "not an STL file (neither a binary one of the size its triangle count gives, nor ASCII starting with 'solid')".into(),
    ))
}

fn binary(bytes: &[u8], count: usize) -> std::result::Result<Vec<[f64; 3]>, String> {
    let mut out = Vec::with_capacity(3 * count);
    for t in 0..count {
        let tri = &bytes[84 + 50 * t..84 + 50 * t + 50];
        for v in 0..3 {
            let at = 12 + 12 * v;
            let p: [f64; 3] = std::array::from_fn(|k| {
                let b = &tri[at + 4 * k..at + 4 * k + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            });
            if p.iter().any(|x| !x.is_finite()) {
                return Err(format!("triangle {} has a non-finite vertex", t + 1));
            }
            out.push(p);
        }
    }
    Ok(out)
}

fn ascii(bytes: &[u8]) -> std::result::Result<Vec<[f64; 3]>, String> {
    let text =
        std::str::from_utf8(bytes).map_err(|_| "an ASCII STL that is not text".to_string())?;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("vertex") {
            continue;
        }
        let p: Vec<f64> = words
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| format!("line {}: a vertex that is not three numbers", k + 1))?;
        match p[..] {
            [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => out.push([x, y, z]),
            _ => {
                return Err(format!(
                    "line {}: a vertex that is not three finite numbers",
                    k + 1
                ))
            }
        }
    }
    if out.is_empty() {
        return Err("an ASCII STL with no vertex".into());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A binary STL of the given triangles.
    pub(crate) fn binary_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut b = vec![0u8; 80];
        b.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for t in triangles {
            b.extend_from_slice(&[0u8; 12]);
            for v in t {
                for x in v {
                    b.extend_from_slice(&x.to_le_bytes());
                }
            }
            b.extend_from_slice(&[0u8; 2]);
        }
        b
    }

    #[test]
    fn binary_and_ascii_files_give_their_vertices() {
        let tri = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.5]];
        let v = vertices(&binary_stl(&[tri])).unwrap();
        assert_eq!(v, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.5]]);
        let text = "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 2 0.5\n  endloop\n endfacet\nendsolid t\n";
        assert_eq!(vertices(text.as_bytes()).unwrap(), v);
    }

    #[test]
    fn a_file_that_is_no_stl_is_refused_with_a_reason() {
        let e = |b: &[u8]| vertices(b).unwrap_err().to_string();
        assert!(e(b"hello").contains("not an STL"));
        assert!(e(b"solid x\nvertex 1 2\n").contains("line 2"));
        assert!(e(b"solid x\nvertex 1 2 nan\n").contains("finite"));
        assert!(e(b"solid x\nendsolid\n").contains("no vertex"));
        let mut cut = binary_stl(&[[[0.0; 3]; 3]]);
        cut.pop();
        assert!(e(&cut).contains("not an STL"));
        let nan = binary_stl(&[[[f32::NAN, 0.0, 0.0], [0.0; 3], [0.0; 3]]]);
        assert!(e(&nan).contains("non-finite"));
    }
}

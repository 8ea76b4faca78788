//! A Wavefront OBJ surface, read straight into its corners and triangles: a line at a time into
//! one buffer, each vertex (`v`) kept once as written and each face (`f`) as triangles by their
//! corners' numbers, so that nothing is held twice and no line, face or map of vertices is
//! made on the way (`docs/performance.md`, "Foundations of faces"). A face of more than three
//! corners is fanned from its first (corners 1 2 3, then 1 3 4, …), triangles in the faces'
//! order. Only where the rock is matters: texture coordinates, normals, objects, groups,
//! materials, smoothing, lines and points are passed over. The file's size is bounded by its
//! caller (`files.rs`).

use crate::geometry::ground::SurfaceError;
use std::io::BufRead;

/// A surface as its file gives it: the vertices (X, Y, Z) in the file's order, and the
/// triangles, each by its corners' numbers among them (from 0), in the faces' order.
#[derive(Debug, Default, PartialEq)]
pub struct ObjSurface {
    /// The vertices, each once.
    pub vertices: Vec<[f64; 3]>,
    /// The triangles by their corners' numbers.
    pub triangles: Vec<[u32; 3]>,
}

/// Why a file is not a surface.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObjError {
    /// The file could not be read (the system's reason).
    #[error("cannot read the file: {0}")]
    Read(String),
    /// The file grew past its bound (bytes) while it was read.
    #[error("the file grew past the {0} bytes an input may have")]
    TooLong(u64),
    /// A line (numbered from 1) that is not what its statement needs.
    #[error("not a Wavefront OBJ surface: line {line}: {fault}")]
    Line {
        /// Its number.
        line: usize,
        /// What is wrong with it.
        fault: LineFault,
    },
    /// A triangle the ground cannot be made of, by the line (from 1) of the face it came from.
    #[error("line {line}: {error}")]
    Face {
        /// The face's line.
        line: usize,
        /// What is wrong with its triangle.
        error: SurfaceError,
    },
    /// A surface the ground cannot be made of, as a whole (no triangles, too many).
    #[error("{0}")]
    Surface(SurfaceError),
}

/// What is wrong with a line of a surface file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LineFault {
    /// A vertex's word that is not a number.
    #[error("`{0}` is not a number")]
    NotNumber(String),
    /// A vertex of other than 3, 4 or 6 numbers.
    #[error("a vertex has 3 coordinates, then a weight or 3 colour components; not {0} numbers")]
    VertexNumbers(usize),
    /// A vertex whose weight is zero.
    #[error("a vertex's weight is zero")]
    ZeroWeight,
    /// A vertex with a coordinate that is not a finite number (`inf`, `nan`, `1e999`, or one
    /// its weight takes past the largest number).
    #[error("a vertex's coordinates must be finite numbers")]
    NotFinite,
    /// A face's corner whose vertex number is not a whole number.
    #[error("`{0}` is not a vertex number")]
    NotCorner(String),
    /// A face naming a vertex not written before it (as written: from 1, or back from the last
    /// when negative), of `count`.
    #[error("a face names vertex {named}, of {count} written before it")]
    NoVertex {
        /// The number as written.
        named: i64,
        /// The vertices before the face.
        count: usize,
    },
    /// A face of fewer than three corners.
    #[error("a face has {0} corners, fewer than three")]
    FewCorners(usize),
    /// More vertices than a surface may have.
    #[error("more than 4 294 967 295 vertices")]
    TooManyVertices,
}

/// The surface in `reader`, of at most `limit` bytes.
pub fn read_obj(mut reader: impl BufRead, limit: u64) -> Result<ObjSurface, ObjError> {
    let mut surface = ObjSurface::default();
    let mut line = Vec::with_capacity(256);
    let (mut number, mut read) = (0, 0u64);
    loop {
        line.clear();
        let got = reader
            .read_until(b'\n', &mut line)
            .map_err(|e| ObjError::Read(e.to_string()))?;
        if got == 0 {
            return Ok(surface);
        }
        read += got as u64;
        if read > limit {
            return Err(ObjError::TooLong(limit));
        }
        number += 1;
        let text = match line.strip_prefix("\u{feff}".as_bytes()) {
            Some(rest) if number == 1 => rest,
            _ => &line[..],
        };
        let mut words = Words(text);
        let done = match words.next() {
            Some(b"v") => surface.vertex(words),
            Some(b"f") => surface.face(words),
            _ => Ok(()),
        };
        done.map_err(|fault| ObjError::Line {
            line: number,
            fault,
        })?;
    }
}

/// The line (from 1) of the face that made triangle `triangle` (from 0) of the surface in
/// `reader`, as [`read_obj`] fans faces into triangles: read again, only where a triangle is
/// found wrong, so that no line number is kept for every triangle. `None` past the last.
pub fn face_line(mut reader: impl BufRead, triangle: usize) -> Option<usize> {
    let (mut line, mut number, mut made) = (Vec::with_capacity(256), 0, 0usize);
    loop {
        line.clear();
        if reader.read_until(b'\n', &mut line).ok()? == 0 {
            return None;
        }
        number += 1;
        let mut words = Words(&line);
        if words.next() == Some(b"f") {
            made += words.count().saturating_sub(2);
            if made > triangle {
                return Some(number);
            }
        }
    }
}

impl ObjSurface {
    /// `v x y z`, `v x y z w` (each coordinate divided by w) or `v x y z r g b` (the colour
    /// passed over).
    fn vertex(&mut self, words: Words) -> Result<(), LineFault> {
        let mut v = [0.0; 4];
        let mut count = 0;
        for w in words {
            if count < 4 {
                v[count] = number(w)?;
            }
            count += 1;
        }
        let [x, y, z, w] = v;
        let corner = match count {
            3 | 6 => [x, y, z],
            4 if w == 0.0 => return Err(LineFault::ZeroWeight),
            4 => [x / w, y / w, z / w],
            _ => return Err(LineFault::VertexNumbers(count)),
        };
        if !corner.iter().all(|x| x.is_finite()) {
            return Err(LineFault::NotFinite);
        }
        if self.vertices.len() > u32::MAX as usize {
            return Err(LineFault::TooManyVertices);
        }
        self.vertices.push(corner);
        Ok(())
    }

    /// `f a b c …`, each corner `v`, `v/vt`, `v//vn` or `v/vt/vn`: the vertex `v` named.
    fn face(&mut self, words: Words) -> Result<(), LineFault> {
        let count = self.vertices.len();
        let (mut first, mut last, mut corners) = (0, 0, 0);
        for w in words {
            let k = corner(w, count)?;
            match corners {
                0 => first = k,
                1 => {}
                _ => self.triangles.push([first, last, k]),
            }
            last = k;
            corners += 1;
        }
        if corners < 3 {
            return Err(LineFault::FewCorners(corners));
        }
        Ok(())
    }
}

/// A line's words, split at ASCII white space.
struct Words<'a>(&'a [u8]);

impl<'a> Iterator for Words<'a> {
    type Item = &'a [u8];

    fn next(&mut self) -> Option<&'a [u8]> {
        let start = self.0.iter().position(|b| !b.is_ascii_whitespace())?;
        let rest = &self.0[start..];
        let end = rest
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(rest.len());
        self.0 = &rest[end..];
        Some(&rest[..end])
    }
}

/// A number as Rust reads an `f64` (correctly rounded): a plain decimal at once, anything else
/// (an exponent, many digits, `inf`) by `str::parse`.
fn number(word: &[u8]) -> Result<f64, LineFault> {
    plain_decimal(word)
        .or_else(|| std::str::from_utf8(word).ok()?.parse().ok())
        .ok_or_else(|| LineFault::NotNumber(String::from_utf8_lossy(word).into_owned()))
}

/// The exact powers of ten an `f64` holds.
const TENS: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A decimal written `[-+]digits[.digits]` whose digits make a whole number below 2⁵³ with at
/// most 22 after the point: that number divided by the power of ten, both exact, so one
/// rounding, the correctly rounded value `str::parse` gives (by the same path, Clinger's). `None`
/// for any other word.
fn plain_decimal(word: &[u8]) -> Option<f64> {
    let (negative, rest) = match word {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, word),
    };
    let (mut whole, mut digits, mut decimals, mut point) = (0u64, 0, 0, false);
    for &b in rest {
        match b {
            b'0'..=b'9' if digits < 19 => {
                whole = whole * 10 + u64::from(b - b'0');
                digits += 1;
                decimals += usize::from(point);
            }
            b'.' if !point => point = true,
            _ => return None,
        }
    }
    if digits == 0 || whole >= 1 << 53 || decimals >= TENS.len() {
        return None;
    }
    let v = whole as f64 / TENS[decimals];
    Some(if negative { -v } else { v })
}

/// The vertex (from 0) a face's corner names, of the `count` written before it.
fn corner(word: &[u8], count: usize) -> Result<u32, LineFault> {
    let v = match word.iter().position(|&b| b == b'/') {
        Some(slash) => &word[..slash],
        None => word,
    };
    let not = || LineFault::NotCorner(String::from_utf8_lossy(word).into_owned());
    let (negative, digits) = match v {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, v),
    };
    // Up to 18 significant digits: no overflow.
    let first = digits
        .iter()
        .position(|&d| d != b'0')
        .unwrap_or(digits.len());
    if digits.is_empty() || digits.len() - first > 18 {
        return Err(not());
    }
    let mut named: i64 = 0;
    for &d in &digits[first..] {
        let d = d.wrapping_sub(b'0');
        if d > 9 {
            return Err(not());
        }
        named = named * 10 + i64::from(d);
    }
    let named = if negative { -named } else { named };
    let k = match named {
        1.. => named - 1,
        ..0 => count as i64 + named,
        0 => -1,
    };
    if (0..count as i64).contains(&k) {
        Ok(k as u32)
    } else {
        Err(LineFault::NoVertex { named, count })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<ObjSurface, ObjError> {
        read_obj(text.as_bytes(), 1 << 20)
    }

    fn fault(text: &str) -> (usize, LineFault) {
        match read(text).unwrap_err() {
            ObjError::Line { line, fault } => (line, fault),
            e => panic!("{e}"),
        }
    }

    #[test]
    fn vertices_are_kept_once_and_faces_of_more_corners_fanned_from_the_first() {
        let s = read(
            "# a square and a pentagon\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv -1 0.5 0.5\n\
             f 1 2 3 4\nf 5 1 2 3 4\n",
        )
        .unwrap();
        assert_eq!(s.vertices.len(), 5);
        assert_eq!(s.vertices[4], [-1.0, 0.5, 0.5]);
        assert_eq!(
            s.triangles,
            [[0, 1, 2], [0, 2, 3], [4, 0, 1], [4, 1, 2], [4, 2, 3]]
        );
    }

    #[test]
    fn corners_in_every_form_and_counted_back_name_their_vertices() {
        let s = read(
            "v 0 0 0\nv 1 0 0\nv 0 0 1\nvt 0 0\nvn 0 1 0\nf 1/1/1 2//1 3/1\nf -3 -2 +3\n\
             f 0000000000000000000000001 2 3\n",
        )
        .unwrap();
        assert_eq!(s.triangles, [[0, 1, 2], [0, 1, 2], [0, 1, 2]]);
    }

    #[test]
    fn what_a_surface_does_not_need_is_passed_over() {
        let s = read(
            "\u{feff}mtllib rock.mtl\r\no rock\r\ng part\r\nusemtl stone\r\ns 1\r\n\
             v 0 0 0\r\nv 1 0 0 1 0 0\r\nv 0 0 1\r\nl 1 2\r\np 1\r\nf 1 2 3\r\n#f 3 2 1\r\n\
             this is not a statement\r\n",
        )
        .unwrap();
        assert_eq!(s.vertices.len(), 3);
        assert_eq!(s.triangles, [[0, 1, 2]]);
    }

    #[test]
    fn numbers_are_read_to_the_bit_as_rust_reads_them() {
        let mut seed = 17u64;
        let mut next = |m: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % m
        };
        let mut words: Vec<String> = [
            "0",
            "-0",
            "-0.0",
            "+1.5",
            ".5",
            "5.",
            "0.1",
            "9007199254740991",
            "9007199254740993",
            "0.30000000000000004",
            "123456789012345678901",
            "1e5",
            "-2.5E-3",
            "inf",
            "-NaN",
            "1.0000000000000000000000001",
            "0.0000000000000000000001",
            "1.",
            ".",
        ]
        .map(String::from)
        .to_vec();
        for _ in 0..20_000 {
            let int: String = (0..next(12))
                .map(|_| char::from(b'0' + next(10) as u8))
                .collect();
            let frac: String = (0..next(14))
                .map(|_| char::from(b'0' + next(10) as u8))
                .collect();
            let sign = ["", "-", "+"][next(3) as usize];
            words.push(format!("{sign}{int}.{frac}"));
            words.push(format!("{sign}{int}"));
        }
        for w in &words {
            let rust = w.parse::<f64>().ok();
            let ours = number(w.as_bytes()).ok();
            assert_eq!(
                ours.map(f64::to_bits),
                rust.map(f64::to_bits),
                "`{w}`: {ours:?} against {rust:?}"
            );
        }
    }

    #[test]
    fn a_vertex_with_a_weight_is_divided_by_it() {
        let s = read("v 2 4 6 2\n").unwrap();
        assert_eq!(s.vertices, [[1.0, 2.0, 3.0]]);
        assert_eq!(fault("v 1 2 3\nv 2 4 6 0\n"), (2, LineFault::ZeroWeight));
    }

    #[test]
    fn a_bad_line_is_named_by_its_number_and_fault() {
        assert_eq!(
            fault("v 0 0 0\nv 1 0 0\nf 1 2 9\n"),
            (3, LineFault::NoVertex { named: 9, count: 2 })
        );
        assert_eq!(
            fault("v 0 0 0\nf 1 -2 1\n"),
            (
                2,
                LineFault::NoVertex {
                    named: -2,
                    count: 1
                }
            )
        );
        assert_eq!(
            fault("v 0 0 0\nf 0 1 1\n"),
            (2, LineFault::NoVertex { named: 0, count: 1 })
        );
        // A face naming a vertex written after it.
        assert_eq!(
            fault("v 0 0 0\nf 1 1 2\nv 1 1 1\n"),
            (2, LineFault::NoVertex { named: 2, count: 1 })
        );
        assert_eq!(
            fault("v 0 0 0\nv 1 0 0\nf 1 2\n"),
            (3, LineFault::FewCorners(2))
        );
        assert_eq!(
            fault("v 0 0 0\nf 1 x 1\n"),
            (2, LineFault::NotCorner("x".into()))
        );
        assert_eq!(
            fault("v 0 0 0\nf 1 99999999999999999999 1\n"),
            (2, LineFault::NotCorner("99999999999999999999".into()))
        );
        assert_eq!(
            fault("v 0 zero 0\n"),
            (1, LineFault::NotNumber("zero".into()))
        );
        assert_eq!(fault("\n\nv 0 0\n"), (3, LineFault::VertexNumbers(2)));
        assert_eq!(fault("v 0 0 0 1 1\n"), (1, LineFault::VertexNumbers(5)));
        let e = read("v 0 0 0\nf 1 2 3\n").unwrap_err().to_string();
        assert!(e.contains("OBJ") && e.contains("line 2"), "{e}");
    }

    #[test]
    fn a_vertex_that_is_not_finite_is_refused_at_its_line() {
        for v in [
            "v inf 0 0",
            "v 0 nan 0",
            "v 0 0 -inf",
            "v 0 1e999 0",
            "v 1e308 0 0 1e-10",
        ] {
            assert_eq!(
                fault(&format!("v 0 0 0\n\n{v}\n")),
                (3, LineFault::NotFinite),
                "{v}"
            );
        }
    }

    #[test]
    fn a_triangles_face_is_found_by_its_number_as_faces_are_fanned() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n\nf 1 2 3 4\n# f 1 2 3\nf 1 2 3\n";
        let at = |k| face_line(text.as_bytes(), k);
        assert_eq!(
            (at(0), at(1), at(2), at(3)),
            (Some(6), Some(6), Some(8), None)
        );
    }

    #[test]
    fn a_file_longer_than_its_bound_is_refused() {
        let text = "v 0 0 0\n".repeat(10);
        assert_eq!(read_obj(text.as_bytes(), 79), Err(ObjError::TooLong(79)));
        assert_eq!(read_obj(text.as_bytes(), 80).unwrap().vertices.len(), 10);
    }
}

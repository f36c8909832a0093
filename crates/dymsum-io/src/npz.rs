//! NumPy `.npz` archives of plain arrays, written atomically.
//!
//! An `.npz` is a ZIP archive of `.npy` files, one per array. Arrays here
//! are `float64`, `int64` or fixed-width unicode strings (`<U…`), so the
//! archive loads with `np.load(path, allow_pickle=False)`. Entries are
//! stored (no compression: the arrays are floats that barely compress, and
//! storing keeps writing at disk speed). The format is tiny:
//!
//! * **NPY 1.0**: the magic `\x93NUMPY`, version `1 0`, a little-endian
//!   `u16` header length, then an ASCII Python dict literal
//!   `{'descr': '<f8', 'fortran_order': False, 'shape': (n, 3), }` padded
//!   with spaces and ending in a newline so that the data starts at a
//!   multiple of 64 bytes; then the data, C order, little-endian.
//! * **ZIP**: per entry a local header (method 0 "stored", CRC-32, sizes)
//!   and the bytes; then the central directory and its end record. Sizes
//!   and offsets are 32-bit: an archive over 4 GiB is refused (split the
//!   map) rather than written in the ZIP64 extension.
//!
//! ```
//! use dymsum_io::npz::{write_npz, Array};
//! let dir = std::env::temp_dir().join(format!("dymsum-npz-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("a.npz");
//! write_npz(&path, &[
//!     Array::f64("x", vec![2, 3], vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]),
//!     Array::i64("n", vec![], vec![7]),
//!     Array::str("names", vec!["r0".into(), "o0".into()]),
//! ])?;
//! let bytes = std::fs::read(&path)?;
//! assert_eq!(&bytes[..4], b"PK\x03\x04");
//! std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::atomic::{write_atomic, FileError};
use std::io::{self, Write};
use std::path::Path;

/// The data of one array.
#[derive(Clone, Debug, PartialEq)]
pub enum Data {
    /// `float64`.
    F64(Vec<f64>),
    /// `int64`.
    I64(Vec<i64>),
    /// Unicode strings, stored as `<U{n}` with `n` the longest (in
    /// characters, at least 1).
    Str(Vec<String>),
}

/// One named array: a shape (C order) and its data.
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    /// The entry name, without `.npy`.
    pub name: String,
    /// The shape; `[]` for a scalar.
    pub shape: Vec<usize>,
    /// The elements, `shape.iter().product()` of them.
    pub data: Data,
}

impl Array {
    /// A `float64` array.
    pub fn f64(name: &str, shape: Vec<usize>, data: Vec<f64>) -> Array {
        Array {
            name: name.into(),
            shape,
            data: Data::F64(data),
        }
    }
    /// An `int64` array.
    pub fn i64(name: &str, shape: Vec<usize>, data: Vec<i64>) -> Array {
        Array {
            name: name.into(),
            shape,
            data: Data::I64(data),
        }
    }
    /// A 1-D array of strings.
    pub fn str(name: &str, data: Vec<String>) -> Array {
        Array {
            name: name.into(),
            shape: vec![data.len()],
            data: Data::Str(data),
        }
    }

    fn len(&self) -> usize {
        match &self.data {
            Data::F64(v) => v.len(),
            Data::I64(v) => v.len(),
            Data::Str(v) => v.len(),
        }
    }

    /// The `.npy` bytes: header, then data.
    fn npy(&self) -> io::Result<Vec<u8>> {
        let count: usize = self.shape.iter().product();
        if count != self.len() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "array {}: shape {:?} holds {count} elements, the data {}",
                    self.name,
                    self.shape,
                    self.len()
                ),
            ));
        }
        let width = match &self.data {
            Data::Str(v) => v
                .iter()
                .map(|s| s.chars().count())
                .max()
                .unwrap_or(0)
                .max(1),
            _ => 8,
        };
        let descr = match &self.data {
            Data::F64(_) => "<f8".to_string(),
            Data::I64(_) => "<i8".to_string(),
            Data::Str(_) => format!("<U{width}"),
        };
        let shape = match self.shape.as_slice() {
            [] => "()".to_string(),
            [n] => format!("({n},)"),
            s => format!(
                "({})",
                s.iter()
                    .map(|n| n.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        let mut header =
            format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
        // Magic (6) + version (2) + length (2) + header + '\n' ≡ 0 mod 64.
        let total = 10 + header.len() + 1;
        header.extend(std::iter::repeat_n(' ', total.next_multiple_of(64) - total));
        header.push('\n');
        let item = match &self.data {
            Data::Str(_) => 4 * width,
            _ => 8,
        };
        let mut out = Vec::with_capacity(10 + header.len() + item * count);
        out.extend_from_slice(b"\x93NUMPY\x01\x00");
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        match &self.data {
            Data::F64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Data::I64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Data::Str(v) => {
                for s in v {
                    let n = s.chars().count();
                    s.chars()
                        .for_each(|c| out.extend_from_slice(&(c as u32).to_le_bytes()));
                    out.extend(std::iter::repeat_n(0u8, 4 * (width - n)));
                }
            }
        }
        Ok(out)
    }
}

/// A writer that counts the bytes through it.
struct Counting<'w> {
    inner: &'w mut dyn Write,
    count: u64,
}

impl Write for Counting<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.count += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

fn too_large(what: &str) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("{what} exceeds 4 GiB, the limit of a ZIP archive without ZIP64; split the map"),
    )
}

fn u32_of(x: u64, what: &str) -> io::Result<u32> {
    u32::try_from(x).map_err(|_| too_large(what))
}

/// Writes `arrays` as an `.npz` to `w` (module docs).
///
/// # Errors
/// A name that is empty or repeated, a shape that does not match its data,
/// an archive over 4 GiB or more than 65,535 arrays, or a write error.
pub fn write_npz_to(w: &mut dyn Write, arrays: &[Array]) -> io::Result<()> {
    let invalid = |m: String| io::Error::new(io::ErrorKind::InvalidInput, m);
    if arrays.len() > u16::MAX as usize {
        return Err(invalid(format!("{} arrays: at most 65,535", arrays.len())));
    }
    let mut w = Counting { inner: w, count: 0 };
    // 1980-01-01 00:00, the earliest DOS date: reproducible archives.
    const TIME: u16 = 0;
    const DATE: u16 = 0x21;
    let mut central = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for a in arrays {
        if a.name.is_empty() || !seen.insert(a.name.as_str()) {
            return Err(invalid(format!(
                "array name `{}` empty or repeated",
                a.name
            )));
        }
        let name = format!("{}.npy", a.name);
        let data = a.npy()?;
        let crc = crc32fast::hash(&data);
        let size = u32_of(data.len() as u64, &name)?;
        let offset = u32_of(w.count, "the archive")?;
        let fixed = |sig: u32, out: &mut Vec<u8>| {
            out.extend_from_slice(&sig.to_le_bytes());
            out.extend_from_slice(&20u16.to_le_bytes()); // version needed (2.0)
            out.extend_from_slice(&0u16.to_le_bytes()); // flags
            out.extend_from_slice(&0u16.to_le_bytes()); // method: stored
            out.extend_from_slice(&TIME.to_le_bytes());
            out.extend_from_slice(&DATE.to_le_bytes());
            out.extend_from_slice(&crc.to_le_bytes());
            out.extend_from_slice(&size.to_le_bytes()); // compressed
            out.extend_from_slice(&size.to_le_bytes()); // uncompressed
            out.extend_from_slice(&(name.len() as u16).to_le_bytes());
            out.extend_from_slice(&0u16.to_le_bytes()); // extra length
        };
        let mut local = Vec::with_capacity(30 + name.len());
        fixed(0x0403_4b50, &mut local);
        local.extend_from_slice(name.as_bytes());
        w.write_all(&local)?;
        w.write_all(&data)?;
        // Central entry: "version made by" precedes the same fields.
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes()); // made by
        let mut rest = Vec::new();
        fixed(0, &mut rest);
        central.extend_from_slice(&rest[4..]);
        central.extend_from_slice(&0u16.to_le_bytes()); // comment length
        central.extend_from_slice(&0u16.to_le_bytes()); // disk
        central.extend_from_slice(&0u16.to_le_bytes()); // internal attributes
        central.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let start = u32_of(w.count, "the archive")?;
    let size = u32_of(central.len() as u64, "the central directory")?;
    u32_of(w.count + central.len() as u64, "the archive")?;
    w.write_all(&central)?;
    let n = arrays.len() as u16;
    let mut end = Vec::with_capacity(22);
    end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes()); // this disk
    end.extend_from_slice(&0u16.to_le_bytes()); // disk of the directory
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&size.to_le_bytes());
    end.extend_from_slice(&start.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes()); // comment length
    w.write_all(&end)
}

/// Writes `arrays` as an `.npz` at `path`, atomically (a temporary file in
/// the same directory, renamed over `path` once complete): on any error
/// nothing is left at `path` and an earlier file there is unchanged.
///
/// # Errors
/// Those of [`write_npz_to`] and of [`write_atomic`], as
/// [`FileError::Write`] naming `path`.
pub fn write_npz(path: &Path, arrays: &[Array]) -> Result<(), FileError> {
    write_atomic(path, |w| write_npz_to(w, arrays))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_are_aligned_and_name_the_dtype_and_shape() {
        for a in [
            Array::f64("x", vec![2, 3], vec![0.0; 6]),
            Array::i64("n", vec![], vec![7]),
            Array::str("s", vec!["ab".into(), "é".into()]),
        ] {
            let b = a.npy().unwrap();
            let len = u16::from_le_bytes([b[8], b[9]]) as usize;
            assert_eq!((10 + len) % 64, 0);
            let h = std::str::from_utf8(&b[10..10 + len]).unwrap();
            assert!(h.ends_with('\n'));
            match a.data {
                Data::F64(_) => assert!(h.contains("'<f8'") && h.contains("(2, 3)")),
                Data::I64(_) => assert!(h.contains("'<i8'") && h.contains("'shape': ()")),
                Data::Str(_) => {
                    assert!(h.contains("'<U2'") && h.contains("(2,)"));
                    assert_eq!(b.len(), 10 + len + 2 * 2 * 4);
                    assert_eq!(&b[10 + len + 8..10 + len + 12], &0xe9u32.to_le_bytes());
                }
            }
        }
    }

    #[test]
    fn bad_shapes_and_names_are_refused() {
        let mut out = Vec::new();
        let bad = Array::f64("x", vec![2, 2], vec![0.0; 3]);
        assert!(write_npz_to(&mut out, &[bad]).is_err());
        let a = Array::i64("x", vec![1], vec![1]);
        assert!(write_npz_to(&mut out, &[a.clone(), a]).is_err());
    }

    #[test]
    fn the_end_record_points_at_the_directory() {
        let mut out = Vec::new();
        let arrays = [
            Array::i64("a", vec![2], vec![1, 2]),
            Array::str("b", vec!["x".into()]),
        ];
        write_npz_to(&mut out, &arrays).unwrap();
        let end = &out[out.len() - 22..];
        assert_eq!(&end[..4], &0x0605_4b50u32.to_le_bytes());
        let entries = u16::from_le_bytes([end[10], end[11]]);
        let size = u32::from_le_bytes(end[12..16].try_into().unwrap()) as usize;
        let start = u32::from_le_bytes(end[16..20].try_into().unwrap()) as usize;
        assert_eq!(entries, 2);
        assert_eq!(start + size, out.len() - 22);
        assert_eq!(&out[start..start + 4], &0x0201_4b50u32.to_le_bytes());
    }
}

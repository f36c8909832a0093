//! NumPy `.npz` archives of plain arrays, written atomically, and read
//! with bounded memory ([`NpzArchive`]).
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
//!   and the bytes; then the central directory and its end record. A size
//!   or offset past 32 bits (an archive over 4 GiB), or more than 65,534
//!   entries, is written in the ZIP64 extension, as `np.savez` does.
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

mod read;

pub use read::{shape_text, Dtype, EntryInfo, NpyHeader, NpzArchive, NpzError, MAX_HEADER};

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

    /// The `.npy` header: magic, version 1.0, length, then the dict,
    /// padded so that the data starts at a multiple of 64 bytes.
    fn npy_header(&self) -> io::Result<Vec<u8>> {
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
        let dtype = Dtype::of(&self.data);
        let shape: Vec<u64> = self.shape.iter().map(|&d| d as u64).collect();
        let mut header = format!(
            "{{'descr': '{}', 'fortran_order': False, 'shape': {}, }}",
            dtype.descr(),
            shape_text(&shape)
        );
        // Magic (6) + version (2) + length (2) + header + '\n' ≡ 0 mod 64.
        let total = 10 + header.len() + 1;
        header.extend(std::iter::repeat_n(' ', total.next_multiple_of(64) - total));
        header.push('\n');
        let mut out = Vec::with_capacity(10 + header.len());
        out.extend_from_slice(b"\x93NUMPY\x01\x00");
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        Ok(out)
    }

    /// The data's length in bytes.
    fn data_len(&self) -> u64 {
        match &self.data {
            Data::F64(v) => 8 * v.len() as u64,
            Data::I64(v) => 8 * v.len() as u64,
            Data::Str(v) => 4 * (str_width(v) * v.len()) as u64,
        }
    }

    /// The data, C order, little-endian, handed to `f` in pieces of about
    /// 64 KiB (nothing the size of the array is allocated).
    fn data_chunks(&self, f: &mut dyn FnMut(&[u8]) -> io::Result<()>) -> io::Result<()> {
        const CHUNK: usize = 1 << 16;
        let mut buf = Vec::with_capacity(CHUNK);
        match &self.data {
            Data::F64(v) => {
                for c in v.chunks(CHUNK / 8) {
                    buf.clear();
                    buf.extend(c.iter().flat_map(|x| x.to_le_bytes()));
                    f(&buf)?;
                }
            }
            Data::I64(v) => {
                for c in v.chunks(CHUNK / 8) {
                    buf.clear();
                    buf.extend(c.iter().flat_map(|x| x.to_le_bytes()));
                    f(&buf)?;
                }
            }
            Data::Str(v) => {
                let width = str_width(v);
                for s in v {
                    let n = s.chars().count();
                    buf.extend(s.chars().flat_map(|c| (c as u32).to_le_bytes()));
                    buf.extend(std::iter::repeat_n(0u8, 4 * (width - n)));
                    if buf.len() >= CHUNK {
                        f(&buf)?;
                        buf.clear();
                    }
                }
                if !buf.is_empty() {
                    f(&buf)?;
                }
            }
        }
        Ok(())
    }

    /// The `.npy` bytes: header, then data.
    #[cfg(test)]
    fn npy(&self) -> io::Result<Vec<u8>> {
        let mut out = self.npy_header()?;
        self.data_chunks(&mut |c| {
            out.extend_from_slice(c);
            Ok(())
        })?;
        Ok(out)
    }
}

/// The width of the strings' `<U{n}` dtype: the longest, in characters, at
/// least 1.
fn str_width(v: &[String]) -> usize {
    v.iter()
        .map(|s| s.chars().count())
        .max()
        .unwrap_or(0)
        .max(1)
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

/// Writes `arrays` as an `.npz` to `w` (module docs).
///
/// # Errors
/// A name that is empty or repeated, a shape that does not match its data,
/// or a write error.
pub fn write_npz_to(w: &mut dyn Write, arrays: &[Array]) -> io::Result<()> {
    write_npz_zip64_over(w, arrays, u64::from(u32::MAX - 1))
}

/// [`write_npz_to`], with the sizes and offsets over `limit` written in
/// ZIP64 (`limit` below 2³² − 1 only in tests).
fn write_npz_zip64_over(w: &mut dyn Write, arrays: &[Array], limit: u64) -> io::Result<()> {
    let invalid = |m: String| io::Error::new(io::ErrorKind::InvalidInput, m);
    let mut w = Counting { inner: w, count: 0 };
    // 1980-01-01 00:00, the earliest DOS date: reproducible archives.
    const TIME: u16 = 0;
    const DATE: u16 = 0x21;
    const SATURATED: u32 = u32::MAX;
    let small = |x: u64| u32::try_from(x).ok().filter(|_| x <= limit);
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
        let name_len = u16::try_from(name.len())
            .map_err(|_| invalid(format!("array name `{}` too long", a.name)))?;
        // Encoded twice, a piece at a time: for the CRC-32 the local header
        // holds, then to write.
        let head = a.npy_header()?;
        let mut crc = crc32fast::Hasher::new();
        crc.update(&head);
        a.data_chunks(&mut |c| {
            crc.update(c);
            Ok(())
        })?;
        let crc = crc.finalize();
        let (size, offset) = (head.len() as u64 + a.data_len(), w.count);
        // ZIP64 (version 4.5) for a size or offset past 32 bits: the
        // fields saturated, the values in the extra field (id 1).
        let (size32, offset32) = (small(size), small(offset));
        let version: u16 = if size32.is_some() && offset32.is_some() {
            20
        } else {
            45
        };
        let fixed = |sig: u32, extra: usize, out: &mut Vec<u8>| {
            let size = size32.unwrap_or(SATURATED);
            out.extend_from_slice(&sig.to_le_bytes());
            out.extend_from_slice(&version.to_le_bytes()); // version needed
            out.extend_from_slice(&0u16.to_le_bytes()); // flags
            out.extend_from_slice(&0u16.to_le_bytes()); // method: stored
            out.extend_from_slice(&TIME.to_le_bytes());
            out.extend_from_slice(&DATE.to_le_bytes());
            out.extend_from_slice(&crc.to_le_bytes());
            out.extend_from_slice(&size.to_le_bytes()); // compressed
            out.extend_from_slice(&size.to_le_bytes()); // uncompressed
            out.extend_from_slice(&name_len.to_le_bytes());
            out.extend_from_slice(&(extra as u16).to_le_bytes());
        };
        let mut sizes64 = Vec::new();
        if size32.is_none() {
            sizes64.extend_from_slice(&1u16.to_le_bytes());
            sizes64.extend_from_slice(&16u16.to_le_bytes());
            sizes64.extend_from_slice(&size.to_le_bytes()); // uncompressed
            sizes64.extend_from_slice(&size.to_le_bytes()); // compressed
        }
        let mut local = Vec::with_capacity(30 + name.len() + sizes64.len());
        fixed(0x0403_4b50, sizes64.len(), &mut local);
        local.extend_from_slice(name.as_bytes());
        local.extend_from_slice(&sizes64);
        w.write_all(&local)?;
        w.write_all(&head)?;
        a.data_chunks(&mut |c| w.write_all(c))?;
        // Central entry: "version made by" precedes the same fields; its
        // extra field holds the saturated values only, in order.
        let mut values64 = Vec::new();
        if size32.is_none() {
            values64.extend_from_slice(&size.to_le_bytes());
            values64.extend_from_slice(&size.to_le_bytes());
        }
        if offset32.is_none() {
            values64.extend_from_slice(&offset.to_le_bytes());
        }
        let mut extra = Vec::new();
        if !values64.is_empty() {
            extra.extend_from_slice(&1u16.to_le_bytes());
            extra.extend_from_slice(&(values64.len() as u16).to_le_bytes());
            extra.extend_from_slice(&values64);
        }
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&version.to_le_bytes()); // made by
        let mut rest = Vec::new();
        fixed(0, extra.len(), &mut rest);
        central.extend_from_slice(&rest[4..]);
        central.extend_from_slice(&0u16.to_le_bytes()); // comment length
        central.extend_from_slice(&0u16.to_le_bytes()); // disk
        central.extend_from_slice(&0u16.to_le_bytes()); // internal attributes
        central.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        central.extend_from_slice(&offset32.unwrap_or(SATURATED).to_le_bytes());
        central.extend_from_slice(name.as_bytes());
        central.extend_from_slice(&extra);
    }
    let start = w.count;
    let size = central.len() as u64;
    let n = arrays.len() as u64;
    w.write_all(&central)?;
    let (n16, size32, start32) = (
        u16::try_from(n).ok().filter(|&n| n < u16::MAX),
        small(size),
        small(start),
    );
    if n16.is_none() || size32.is_none() || start32.is_none() {
        // The ZIP64 end record, then its locator.
        let at = w.count;
        let mut rec = Vec::with_capacity(76);
        rec.extend_from_slice(&0x0606_4b50u32.to_le_bytes());
        rec.extend_from_slice(&44u64.to_le_bytes()); // the size of what follows
        rec.extend_from_slice(&45u16.to_le_bytes()); // made by
        rec.extend_from_slice(&45u16.to_le_bytes()); // needed
        rec.extend_from_slice(&0u32.to_le_bytes()); // this disk
        rec.extend_from_slice(&0u32.to_le_bytes()); // disk of the directory
        rec.extend_from_slice(&n.to_le_bytes());
        rec.extend_from_slice(&n.to_le_bytes());
        rec.extend_from_slice(&size.to_le_bytes());
        rec.extend_from_slice(&start.to_le_bytes());
        rec.extend_from_slice(&0x0706_4b50u32.to_le_bytes());
        rec.extend_from_slice(&0u32.to_le_bytes()); // disk of the record
        rec.extend_from_slice(&at.to_le_bytes());
        rec.extend_from_slice(&1u32.to_le_bytes()); // disks
        w.write_all(&rec)?;
    }
    let n16 = n16.unwrap_or(u16::MAX);
    let mut end = Vec::with_capacity(22);
    end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes()); // this disk
    end.extend_from_slice(&0u16.to_le_bytes()); // disk of the directory
    end.extend_from_slice(&n16.to_le_bytes());
    end.extend_from_slice(&n16.to_le_bytes());
    end.extend_from_slice(&size32.unwrap_or(SATURATED).to_le_bytes());
    end.extend_from_slice(&start32.unwrap_or(SATURATED).to_le_bytes());
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
    fn zip64_sizes_offsets_and_end_record_read_back() {
        let arrays = [
            Array::i64("a", vec![2], vec![1, 2]),
            Array::str("b", vec!["x".into(), "yz".into()]),
            Array::f64("c", vec![1, 3], vec![0.5, 1.5, 2.5]),
        ];
        let (mut plain, mut wide) = (Vec::new(), Vec::new());
        write_npz_to(&mut plain, &arrays).unwrap();
        // Every size and offset past 0 in ZIP64: what an archive over
        // 4 GiB gets, without writing 4 GiB.
        write_npz_zip64_over(&mut wide, &arrays, 0).unwrap();
        assert!(wide.len() > plain.len());
        assert!(!plain.windows(4).any(|w| w == 0x0606_4b50u32.to_le_bytes()));
        for bytes in [plain, wide] {
            let mut npz = NpzArchive::new(std::io::Cursor::new(bytes)).unwrap();
            for (i, a) in arrays.iter().enumerate() {
                let h = npz.header(i).unwrap();
                assert_eq!(npz.values(i, &h).unwrap(), a.data);
            }
        }
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

//! The restart state in each time directory: named `f64` arrays and scalar metadata, in a small
//! self-checking binary format, read back bit for bit.
//!
//! Layout (every number little-endian):
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `FSIMSTAT` |
//! | 4 | format version, `u32` = 1 |
//! | 8 | payload length in bytes, `u64` (everything between this field and the checksum) |
//! | … | payload: `time` f64, `step` u64, `delta_t` f64; `u32` count of metadata pairs, each a key and a value string; `u32` count of arrays, each a name string, a `u64` value count and the values as f64 |
//! | 4 | CRC-32 (IEEE 802.3, the checksum of gzip and zlib) of all bytes before it |
//!
//! A string is a `u32` byte length followed by UTF-8 bytes. The payload length catches a
//! truncated file before the checksum is computed, so the error says which of the two happened.

use super::output_error::OutputError;
use super::safe_dir::SafeDir;
use crate::case::bounded_read::{read_regular_file, MAX_RESTART_BYTES};
use flate2::Crc;
use std::collections::BTreeMap;
use std::io::{BufWriter, Write};
use std::path::Path;

const MAGIC: &[u8; 8] = b"FSIMSTAT";
const FORMAT_VERSION: u32 = 1;
/// Magic, version and payload length.
const HEADER_BYTES: usize = 8 + 4 + 8;
const CHECKSUM_BYTES: usize = 4;

/// The scalars of a restart: where the run stood.
#[derive(Clone, Debug, PartialEq)]
pub struct RestartHeader {
    /// Simulated time, seconds.
    pub time: f64,
    /// Number of time steps taken since the run's origin.
    pub step: u64,
    /// The time step to continue with, seconds.
    pub delta_t: f64,
    /// Anything else the solver needs to continue (model name, RNG state as text, …).
    pub metadata: BTreeMap<String, String>,
}

/// A restart file read back: the header and the arrays, in the order they were written.
#[derive(Clone, Debug, PartialEq)]
pub struct RestartState {
    pub header: RestartHeader,
    pub arrays: Vec<(String, Vec<f64>)>,
}

impl RestartHeader {
    pub fn new(time: f64, step: u64, delta_t: f64) -> Self {
        RestartHeader {
            time,
            step,
            delta_t,
            metadata: BTreeMap::new(),
        }
    }

    /// Writes this header and the borrowed `arrays` to file `name` of `dir` (conventionally
    /// `<time>/restart.bin`). Array names must be distinct.
    pub fn write(
        &self,
        dir: &SafeDir,
        name: &str,
        arrays: &[(&str, &[f64])],
    ) -> Result<(), OutputError> {
        let path = &dir.join(name);
        for (i, (name, _)) in arrays.iter().enumerate() {
            if arrays[..i].iter().any(|(other, _)| other == name) {
                return Err(OutputError::invalid(
                    path,
                    format!("restart array `{name}` given twice"),
                ));
            }
        }
        let string_bytes = |s: &str| 4 + s.len();
        let payload_len = 8
            + 8
            + 8
            + 4
            + self
                .metadata
                .iter()
                .map(|(k, v)| string_bytes(k) + string_bytes(v))
                .sum::<usize>()
            + 4
            + arrays
                .iter()
                .map(|(name, values)| string_bytes(name) + 8 + 8 * values.len())
                .sum::<usize>();

        let io_err = |e| OutputError::io(path, "cannot write restart file", e);
        let file = dir.create_file(name)?;
        let mut out = ChecksumWriter {
            inner: BufWriter::with_capacity(1 << 20, file),
            crc: Crc::new(),
        };
        let mut body = || -> std::io::Result<()> {
            out.write_all(MAGIC)?;
            out.write_all(&FORMAT_VERSION.to_le_bytes())?;
            out.write_all(&(payload_len as u64).to_le_bytes())?;
            out.write_all(&self.time.to_le_bytes())?;
            out.write_all(&self.step.to_le_bytes())?;
            out.write_all(&self.delta_t.to_le_bytes())?;
            out.write_all(&(self.metadata.len() as u32).to_le_bytes())?;
            for (key, value) in &self.metadata {
                write_string(&mut out, key)?;
                write_string(&mut out, value)?;
            }
            out.write_all(&(arrays.len() as u32).to_le_bytes())?;
            for (name, values) in arrays {
                write_string(&mut out, name)?;
                out.write_all(&(values.len() as u64).to_le_bytes())?;
                write_f64_le(&mut out, values)?;
            }
            let checksum = out.crc.sum();
            out.inner.write_all(&checksum.to_le_bytes())?;
            out.inner.flush()
        };
        body().map_err(io_err)
    }
}

impl RestartState {
    /// Reads a restart file; a wrong magic, a truncated file or a checksum mismatch is an error
    /// naming the file.
    pub fn read(path: &Path) -> Result<Self, OutputError> {
        // as every file a case holds: a regular file only, of bounded size
        let bytes = read_regular_file(path, MAX_RESTART_BYTES)
            .map_err(|e| OutputError::invalid(path, format!("cannot read restart file: {e}")))?;
        Self::from_bytes(path, &bytes)
    }

    /// Decodes the bytes of a restart file; `path` only names the file in errors.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Self, OutputError> {
        let bad = |msg: String| OutputError::invalid(path, format!("corrupt restart file: {msg}"));
        if bytes.len() < HEADER_BYTES + CHECKSUM_BYTES || &bytes[..8] != MAGIC {
            return Err(bad(
                "not an fsim restart file (bad magic or too short)".into()
            ));
        }
        let version = u32::from_le_bytes(bytes[8..12].try_into().unwrap());
        if version != FORMAT_VERSION {
            return Err(bad(format!(
                "format version {version}, this fsim reads version {FORMAT_VERSION}"
            )));
        }
        let payload_len = u64::from_le_bytes(bytes[12..20].try_into().unwrap());
        let expected = (HEADER_BYTES as u64)
            .checked_add(payload_len)
            .and_then(|n| n.checked_add(CHECKSUM_BYTES as u64));
        if expected != Some(bytes.len() as u64) {
            return Err(bad(format!(
                "truncated or padded: header announces {} bytes, file has {}",
                expected.map_or("too many".to_string(), |n| n.to_string()),
                bytes.len()
            )));
        }
        let (body, checksum) = bytes.split_at(bytes.len() - CHECKSUM_BYTES);
        let stored = u32::from_le_bytes(checksum.try_into().unwrap());
        let mut crc = Crc::new();
        crc.update(body);
        if crc.sum() != stored {
            return Err(bad(format!(
                "checksum mismatch (stored {stored:08x}, computed {:08x})",
                crc.sum()
            )));
        }
        let mut cursor = Cursor {
            bytes: &body[HEADER_BYTES..],
        };
        let parse = |cursor: &mut Cursor| -> Option<RestartState> {
            let time = f64::from_le_bytes(cursor.take(8)?.try_into().ok()?);
            let step = u64::from_le_bytes(cursor.take(8)?.try_into().ok()?);
            let delta_t = f64::from_le_bytes(cursor.take(8)?.try_into().ok()?);
            let mut header = RestartHeader::new(time, step, delta_t);
            for _ in 0..cursor.u32()? {
                let key = cursor.string()?;
                let value = cursor.string()?;
                header.metadata.insert(key, value);
            }
            let count = cursor.u32()? as usize;
            let mut arrays = Vec::with_capacity(count.min(1024));
            for _ in 0..count {
                let name = cursor.string()?;
                let len = usize::try_from(cursor.u64()?).ok()?;
                let raw = cursor.take(len.checked_mul(8)?)?;
                let values = raw
                    .chunks_exact(8)
                    .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
                    .collect();
                arrays.push((name, values));
            }
            cursor
                .bytes
                .is_empty()
                .then_some(RestartState { header, arrays })
        };
        parse(&mut cursor).ok_or_else(|| bad("payload does not decode".into()))
    }

    /// The array called `name`.
    pub fn array(&self, name: &str) -> Option<&[f64]> {
        self.arrays
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// The array called `name` with exactly `len` values, or an error naming the file.
    pub fn require(&self, path: &Path, name: &str, len: usize) -> Result<&[f64], OutputError> {
        match self.array(name) {
            Some(v) if v.len() == len => Ok(v),
            Some(v) => Err(OutputError::invalid(
                path,
                format!(
                    "restart array `{name}` has {} values, expected {len}",
                    v.len()
                ),
            )),
            None => Err(OutputError::invalid(
                path,
                format!("restart file has no array `{name}`"),
            )),
        }
    }
}

struct ChecksumWriter<W: Write> {
    inner: W,
    crc: Crc,
}

impl<W: Write> Write for ChecksumWriter<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.crc.update(&buf[..n]);
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

fn write_string(out: &mut impl Write, s: &str) -> std::io::Result<()> {
    out.write_all(&(s.len() as u32).to_le_bytes())?;
    out.write_all(s.as_bytes())
}

fn write_f64_le(out: &mut impl Write, values: &[f64]) -> std::io::Result<()> {
    const CHUNK: usize = 4096;
    let mut buffer = [0u8; CHUNK * 8];
    for chunk in values.chunks(CHUNK) {
        for (slot, v) in buffer.chunks_exact_mut(8).zip(chunk) {
            slot.copy_from_slice(&v.to_le_bytes());
        }
        out.write_all(&buffer[..chunk.len() * 8])?;
    }
    Ok(())
}

struct Cursor<'a> {
    bytes: &'a [u8],
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        if n > self.bytes.len() {
            return None;
        }
        let (head, tail) = self.bytes.split_at(n);
        self.bytes = tail;
        Some(head)
    }

    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }

    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }

    fn string(&mut self) -> Option<String> {
        let len = self.u32()? as usize;
        String::from_utf8(self.take(len)?.to_vec()).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;

    /// SplitMix64: a seeded generator so the test data is the same on every run.
    fn random_bits(seed: u64, n: usize) -> Vec<f64> {
        let mut state = seed;
        (0..n)
            .map(|_| {
                state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                // Arbitrary bit patterns: NaN payloads, subnormals, ±0, ±inf included.
                f64::from_bits(z ^ (z >> 31))
            })
            .collect()
    }

    fn sample(dir: &ScratchDir) -> (std::path::PathBuf, RestartHeader, Vec<f64>, Vec<f64>) {
        let path = dir.path().join("restart.bin");
        let mut header = RestartHeader::new(0.125, 4242, 1.0 / 3.0e5);
        header.metadata.insert("model".into(), "direct".into());
        header.metadata.insert("note".into(), "ünïcode ok".into());
        let u = random_bits(20261123, 10_007);
        let p = random_bits(7, 4096);
        header
            .write(
                &SafeDir::open_case(dir.path()).unwrap(),
                "restart.bin",
                &[("U", &u), ("p", &p), ("empty", &[])],
            )
            .unwrap();
        (path, header, u, p)
    }

    #[test]
    fn round_trip_is_bit_exact() {
        let dir = ScratchDir::new("restart");
        let (path, header, u, p) = sample(&dir);
        let state = RestartState::read(&path).unwrap();
        assert_eq!(state.header.step, header.step);
        assert_eq!(state.header.time.to_bits(), header.time.to_bits());
        assert_eq!(state.header.delta_t.to_bits(), header.delta_t.to_bits());
        assert_eq!(state.header.metadata, header.metadata);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(state.array("U").unwrap()), bits(&u));
        assert_eq!(bits(state.require(&path, "p", 4096).unwrap()), bits(&p));
        assert_eq!(state.array("empty").unwrap().len(), 0);
        let names: Vec<_> = state.arrays.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["U", "p", "empty"]);
        let err = state.require(&path, "p", 5).unwrap_err().to_string();
        assert!(
            err.contains("restart.bin") && err.contains("expected 5"),
            "{err}"
        );
        assert!(state.require(&path, "T", 1).is_err());
    }

    #[test]
    fn corruption_and_truncation_are_detected_naming_the_file() {
        let dir = ScratchDir::new("restart-bad");
        let (path, ..) = sample(&dir);
        let good = std::fs::read(&path).unwrap();

        let mut flipped = good.clone();
        flipped[5000] ^= 0x10;
        let err = RestartState::from_bytes(&path, &flipped)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("restart.bin") && err.contains("checksum"),
            "{err}"
        );

        std::fs::write(&path, &good[..good.len() - 100]).unwrap();
        let err = RestartState::read(&path).unwrap_err().to_string();
        assert!(
            err.contains("restart.bin") && err.contains("truncated"),
            "{err}"
        );

        let err = RestartState::from_bytes(&path, b"hello")
            .unwrap_err()
            .to_string();
        assert!(err.contains("magic"), "{err}");

        let mut versioned = good.clone();
        versioned[8] = 9;
        let err = RestartState::from_bytes(&path, &versioned)
            .unwrap_err()
            .to_string();
        assert!(err.contains("version 9"), "{err}");

        let missing = dir.path().join("nothere.bin");
        let err = RestartState::read(&missing).unwrap_err().to_string();
        assert!(err.contains("nothere.bin"), "{err}");
    }

    #[test]
    fn duplicate_array_names_are_refused() {
        let dir = ScratchDir::new("restart-dup");
        let header = RestartHeader::new(0.0, 0, 1.0);
        let out = SafeDir::open_case(dir.path()).unwrap();
        assert!(header
            .write(&out, "restart.bin", &[("U", &[1.0]), ("U", &[2.0])])
            .is_err());
    }
}

//! The files of a zip archive (a zipped Shapefile; KMZ and zipped TaskData later), read from
//! memory with `rawzip` and inflated with `miniz_oxide`, each checked against its size and CRC.
//! Archives that would unpack to more than [`MAX_UNZIPPED_BYTES`] are refused before anything
//! is inflated past it.
//!
//! ```
//! use furrow::formats::zip::unzip;
//!
//! // Not a zip archive.
//! let e = unzip(b"PK\x03\x04 but nothing more").unwrap_err();
//! assert_eq!(e.code, furrow::ErrorCode::InvalidFile);
//! ```

use crate::error::{ErrorCode, PlanError};
use std::io::Read;

/// The most bytes an archive's files may hold in all, unpacked: a zip of a few kilobytes may
/// unpack to gigabytes.
pub const MAX_UNZIPPED_BYTES: u64 = 256 << 20;

/// The most files an archive may hold.
pub const MAX_ZIP_ENTRIES: usize = 10_000;

/// A file of an archive: its path (`/`-separated, as stored) and its bytes.
#[derive(Debug, Clone)]
pub struct ZipFile {
    /// Its path in the archive.
    pub path: String,
    /// Its contents, unpacked.
    pub bytes: Vec<u8>,
}

/// The files of the zip archive `bytes`, folders left out.
pub fn unzip(bytes: &[u8]) -> Result<Vec<ZipFile>, PlanError> {
    let archive = rawzip::ZipArchive::from_slice(bytes).map_err(|_| damaged("its directory"))?;
    let mut headers = Vec::new();
    let mut entries = archive.entries();
    let mut total: u64 = 0;
    while let Some(entry) = entries.next_entry().map_err(|_| damaged("its directory"))? {
        if entry.is_dir() {
            continue;
        }
        if headers.len() == MAX_ZIP_ENTRIES {
            return Err(too_large(format!(
                "the zip archive holds more than {MAX_ZIP_ENTRIES} files"
            )));
        }
        total = total.saturating_add(entry.uncompressed_size_hint());
        if total > MAX_UNZIPPED_BYTES {
            return Err(unpacks_too_large());
        }
        let path = String::from_utf8_lossy(entry.file_path().as_ref()).into_owned();
        headers.push((path, entry.wayfinder(), entry.compression_method()));
    }
    let mut files = Vec::with_capacity(headers.len());
    for (path, wayfinder, method) in headers {
        let entry = archive
            .get_entry(wayfinder)
            .map_err(|_| damaged(&format!("its file {path}")))?;
        let limit =
            usize::try_from(wayfinder.uncompressed_size_hint()).map_err(|_| unpacks_too_large())?;
        let unpacked = match method {
            rawzip::CompressionMethod::STORE => entry.data().to_vec(),
            rawzip::CompressionMethod::DEFLATE => {
                miniz_oxide::inflate::decompress_to_vec_with_limit(entry.data(), limit)
                    .map_err(|_| damaged(&format!("its file {path}")))?
            }
            _ => {
                return Err(PlanError::new(
                    ErrorCode::InvalidFile,
                    format!("the zip archive's file {path} is compressed in a way furrow does not read (only stored and deflated files): zip it again with the usual settings"),
                ))
            }
        };
        // The size and CRC the archive gives for the file.
        let mut checked = Vec::with_capacity(unpacked.len());
        entry
            .verifying_reader(unpacked.as_slice())
            .read_to_end(&mut checked)
            .map_err(|_| damaged(&format!("its file {path}")))?;
        files.push(ZipFile {
            path,
            bytes: checked,
        });
    }
    Ok(files)
}

/// A zip archive of one file, `path`, deflated.
pub fn zip_one(path: &str, data: &[u8]) -> Result<Vec<u8>, PlanError> {
    // Writing to memory fails only on a bug.
    fn failed<E>(_: E) -> PlanError {
        PlanError::new(ErrorCode::Internal, "the zip archive could not be written")
    }
    let mut out = Vec::new();
    let mut archive = rawzip::ZipArchiveWriter::new(&mut out);
    let (mut entry, config) = archive
        .new_file(path)
        .compression_method(rawzip::CompressionMethod::DEFLATE)
        .start()
        .map_err(failed)?;
    let mut writer = config.wrap(Deflater {
        inner: &mut entry,
        buffer: Vec::new(),
    });
    std::io::Write::write_all(&mut writer, data).map_err(failed)?;
    let (deflater, descriptor) = writer.finish().map_err(failed)?;
    deflater.finish().map_err(failed)?;
    entry.finish(descriptor).map_err(failed)?;
    archive.finish().map_err(failed)?;
    Ok(out)
}

/// Deflates what is written to it, in one piece when finished (`miniz_oxide` has no stream
/// writer; a TaskData file is a few megabytes at most).
struct Deflater<W: std::io::Write> {
    inner: W,
    buffer: Vec<u8>,
}

impl<W: std::io::Write> std::io::Write for Deflater<W> {
    fn write(&mut self, data: &[u8]) -> std::io::Result<usize> {
        self.buffer.extend_from_slice(data);
        Ok(data.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl<W: std::io::Write> Deflater<W> {
    fn finish(mut self) -> std::io::Result<W> {
        let compressed = miniz_oxide::deflate::compress_to_vec(&self.buffer, 6);
        self.inner.write_all(&compressed)?;
        Ok(self.inner)
    }
}

fn damaged(what: &str) -> PlanError {
    PlanError::new(
        ErrorCode::InvalidFile,
        format!("the zip archive is damaged or incomplete ({what} cannot be read): download or copy it again"),
    )
}

fn too_large(message: String) -> PlanError {
    PlanError::new(ErrorCode::InputTooLarge, message)
}

fn unpacks_too_large() -> PlanError {
    too_large(format!(
        "the zip archive unpacks to more than {} MB",
        MAX_UNZIPPED_BYTES >> 20
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stored (uncompressed) archive of one file, as a zip tool writes it.
    fn stored(name: &str, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut archive = rawzip::ZipArchiveWriter::new(&mut out);
        let (mut entry, config) = archive
            .new_file(name)
            .compression_method(rawzip::CompressionMethod::STORE)
            .start()
            .unwrap();
        let mut writer = config.wrap(&mut entry);
        std::io::Write::write_all(&mut writer, data).unwrap();
        let (_, descriptor) = writer.finish().unwrap();
        entry.finish(descriptor).unwrap();
        archive.finish().unwrap();
        out
    }

    #[test]
    fn a_stored_file_comes_back_and_a_cut_archive_is_damaged() {
        let zip = stored("field/field.prj", b"GEOGCS[\"GCS_WGS_1984\"]");
        let files = unzip(&zip).unwrap();
        assert_eq!(files.len(), 1);
        assert_eq!(files[0].path, "field/field.prj");
        assert_eq!(files[0].bytes, b"GEOGCS[\"GCS_WGS_1984\"]");
        for cut in [zip.len() / 2, zip.len() - 1, 10, 0] {
            assert_eq!(
                unzip(&zip[..cut]).unwrap_err().code,
                ErrorCode::InvalidFile,
                "cut at {cut}"
            );
        }
    }

    #[test]
    fn a_zip_written_reads_back() {
        let text = "<ISO11783_TaskData/>".repeat(100);
        let zip = zip_one("TASKDATA/TASKDATA.XML", text.as_bytes()).unwrap();
        assert!(zip.len() < text.len() / 4, "deflated: {} bytes", zip.len());
        let files = unzip(&zip).unwrap();
        assert_eq!(files[0].path, "TASKDATA/TASKDATA.XML");
        assert_eq!(files[0].bytes, text.as_bytes());
    }

    #[test]
    fn a_changed_byte_fails_the_crc() {
        let mut zip = stored("a.txt", b"hello field");
        let at = zip.windows(5).position(|w| w == b"hello").unwrap();
        zip[at] = b'j';
        assert_eq!(unzip(&zip).unwrap_err().code, ErrorCode::InvalidFile);
    }
}

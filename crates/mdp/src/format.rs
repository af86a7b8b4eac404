//! The map file format: TOML with an ASCII layout.
//!
//! ```toml
//! name = "tiny"
//! description = "optional free text"
//! layout = '''
//! ..G
//! .#.
//! '''
//! ```
//!
//! `layout` lists the interior rows from top to bottom: `#` an obstacle, `.` an empty cell,
//! `G` the goal. The boundary of obstacles around the interior is implicit and never drawn.
//! Leading and trailing blank lines of the layout are ignored, and so is whitespace around
//! each row, so a layout may be indented. Unknown keys are refused.
//!
//! Only regular files are read (a directory, a device or a pipe is refused before it is
//! opened, so a FIFO cannot block the reader), and reading stops after
//! [`MAX_FILE_BYTES`] bytes whatever the file's metadata says, so a file that grows while
//! it is read cannot exhaust memory. Errors name the file and, where there is one, the
//! line and column.

use std::io::Read;
use std::path::Path;

use serde::Deserialize;

use crate::error::{MapError, Position};
use crate::map::{LayoutOrigin, Map};

/// The largest map file accepted, in bytes (a full `MAX_SIDE` square layout is about 66 kB).
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The raw shape of a map file, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MapFile {
    name: String,
    description: Option<String>,
    layout: toml::Spanned<String>,
}

impl Map {
    /// Read and validate a map file.
    ///
    /// Errors name the file and, where there is one, the line and column.
    ///
    /// ```
    /// let dir = std::env::temp_dir().join("mdp-doc-map-load");
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("m.toml");
    /// std::fs::write(&path, "name = \"m\"\nlayout = '''\n.G\n'''\n").unwrap();
    /// let map = mdp::Map::load(&path).unwrap();
    /// assert_eq!(map.name(), "m");
    /// ```
    pub fn load(path: &Path) -> Result<Map, MapError> {
        let source = path.display().to_string();
        let bytes = read_regular_file(path, MAX_FILE_BYTES).map_err(|e| match e {
            ReadFailure::Io(e) => MapError::Io {
                source_name: source.clone(),
                error: e.to_string(),
            },
            ReadFailure::NotAFile => MapError::NotAFile {
                source_name: source.clone(),
            },
            ReadFailure::TooLarge { bytes } => MapError::FileTooLarge {
                source_name: source.clone(),
                bytes,
                max: MAX_FILE_BYTES,
            },
        })?;
        Map::from_toml_bytes(&bytes, &source)
    }

    /// Parse and validate a map from the bytes of a TOML file; `source_name` names it in errors.
    ///
    /// ```
    /// let err = mdp::Map::from_toml_bytes(b"\xff\xfe", "bad.toml").unwrap_err();
    /// assert!(err.to_string().contains("bad.toml"));
    /// ```
    pub fn from_toml_bytes(bytes: &[u8], source_name: &str) -> Result<Map, MapError> {
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(MapError::FileTooLarge {
                source_name: source_name.to_string(),
                bytes: bytes.len() as u64,
                max: MAX_FILE_BYTES,
            });
        }
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let (line, column) = line_col(bytes, e.valid_up_to());
            MapError::NotUtf8 {
                source_name: source_name.to_string(),
                at: Position { line, column },
            }
        })?;
        Map::from_toml_str(text, source_name)
    }

    /// Parse and validate a map from TOML text; `source_name` names it in errors.
    ///
    /// ```
    /// let text = "name = \"demo\"\nlayout = '''\nG..\n'''\n";
    /// let map = mdp::Map::from_toml_str(text, "demo.toml").unwrap();
    /// assert_eq!(map.width(), 3);
    /// let err = mdp::Map::from_toml_str("name = \"x\"\ncolour = 1\nlayout = 'G.'", "x.toml").unwrap_err();
    /// assert!(err.to_string().contains("colour"));
    /// ```
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Map, MapError> {
        let file: MapFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| {
                let (line, column) = line_col(text.as_bytes(), s.start);
                Position { line, column }
            });
            MapError::Toml {
                source_name: source_name.to_string(),
                at,
                message: e.message().trim().to_string(),
            }
        })?;
        if file.name.trim().is_empty() {
            return Err(MapError::EmptyName {
                source_name: source_name.to_string(),
            });
        }
        let span = file.layout.span();
        let origin = layout_origin(text, span.start, span.end, file.layout.get_ref());
        Map::build(
            file.name,
            file.description,
            file.layout.get_ref(),
            source_name,
            origin,
        )
    }

    /// The map as a TOML map file that [`Map::from_toml_str`] reads back.
    ///
    /// ```
    /// let map = mdp::builtin("tan3x3").unwrap();
    /// let back = mdp::Map::from_toml_str(&map.to_toml(), "copy").unwrap();
    /// assert_eq!(back, map);
    /// ```
    pub fn to_toml(&self) -> String {
        let mut s = format!("name = {}\n", toml_string(self.name()));
        if let Some(d) = self.description() {
            s.push_str(&format!("description = {}\n", toml_string(d)));
        }
        s.push_str("layout = '''\n");
        s.push_str(&self.layout());
        s.push_str("'''\n");
        s
    }
}

fn toml_string(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// Find where the layout's content starts in the file, when it appears there verbatim.
fn layout_origin(text: &str, start: usize, end: usize, value: &str) -> LayoutOrigin {
    let Some(raw) = text.get(start..end) else {
        return LayoutOrigin::LayoutRelative;
    };
    let (open, verbatim) = if raw.starts_with("'''") {
        (3, true)
    } else if raw.starts_with("\"\"\"") {
        (3, !raw.contains('\\'))
    } else if raw.starts_with('\'') {
        (1, true)
    } else {
        (1, !raw.contains('\\'))
    };
    if !verbatim {
        return LayoutOrigin::LayoutRelative;
    }
    let mut content = start + open;
    // TOML drops a newline that immediately follows the opening delimiter.
    if open == 3 {
        if text[content..].starts_with("\r\n") {
            content += 2;
        } else if text[content..].starts_with('\n') {
            content += 1;
        }
    }
    if !text[content..].starts_with(value) {
        return LayoutOrigin::LayoutRelative;
    }
    let (line, column) = line_col(text.as_bytes(), content);
    LayoutOrigin::File { line, column }
}

/// 1-based line and column (in characters) of a byte offset.
fn line_col(bytes: &[u8], offset: usize) -> (usize, usize) {
    let before = &bytes[..offset.min(bytes.len())];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let column = String::from_utf8_lossy(&before[line_start..])
        .chars()
        .count()
        + 1;
    (line, column)
}

/// Why [`read_regular_file`] read nothing.
pub(crate) enum ReadFailure {
    /// The operating system refused.
    Io(std::io::Error),
    /// A directory, a device, a pipe or a socket.
    NotAFile,
    /// More than the limit: the file's size, or the bytes read before stopping.
    TooLarge { bytes: u64 },
}

/// Read a regular file of at most `max` bytes.
///
/// Non-files are refused from their metadata before they are opened (opening a FIFO
/// would block until a writer appears), and the read itself stops after `max + 1` bytes,
/// so a file that grows while it is read, or lies about its size, cannot exhaust memory.
pub(crate) fn read_regular_file(path: &Path, max: u64) -> Result<Vec<u8>, ReadFailure> {
    let meta = std::fs::metadata(path).map_err(ReadFailure::Io)?;
    if !meta.is_file() {
        return Err(ReadFailure::NotAFile);
    }
    if meta.len() > max {
        return Err(ReadFailure::TooLarge { bytes: meta.len() });
    }
    let file = std::fs::File::open(path).map_err(ReadFailure::Io)?;
    // The path may have been replaced between the two calls: judge what was opened.
    if !file.metadata().map_err(ReadFailure::Io)?.is_file() {
        return Err(ReadFailure::NotAFile);
    }
    let mut bytes = Vec::new();
    file.take(max.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(ReadFailure::Io)?;
    if bytes.len() as u64 > max {
        return Err(ReadFailure::TooLarge {
            bytes: bytes.len() as u64,
        });
    }
    Ok(bytes)
}

//! A level carried whole in a web address, so that any static host serves the page and the link
//! is the exercise: `PAGE#level=DATA&name=FILE.ron`, DATA the level file's text compressed with
//! raw DEFLATE and written in base64url without padding (RFC 4648 section 5: only letters,
//! digits, `-` and `_`, which no URL escapes). It sits in the fragment (after `#`), which a browser never sends
//! to the server: no server limit on the request line applies and no server log keeps the level.
//! `name` keeps the file's name, which a level with parameters needs (a student's numbers
//! depend on it, docs/levels.md).
//!
//! `rigidlab link LEVEL` writes the link and the web page (`app/web.rs`) opens it, both through
//! this module. A link that does not decode says why (bad base64 at a character, bad DEFLATE, too
//! large, not UTF-8) and the page shows that and no other exercise.

use super::{LevelError, Scene, MAX_LEVEL_BYTES};
use std::path::Path;

/// The fragment's key for the level's data.
pub const LEVEL_KEY: &str = "level";
/// The fragment's key for the level's file name.
pub const NAME_KEY: &str = "name";
/// The file name a link without `name=` opens under.
pub const DEFAULT_NAME: &str = "link.ron";

/// DEFLATE at miniz's highest level (a link is made once and opened many times: the few
/// milliseconds more it costs to make buy a shorter link).
const LEVEL: u8 = 10;

/// Why a link's level could not be read out of it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LinkError {
    #[error("there is no level in it (no #{LEVEL_KEY}=...)")]
    Missing,
    #[error("its data is not valid base64url at character {position}: {why}")]
    Base64 { position: usize, why: String },
    #[error("its data does not decompress (damaged or cut short): {0}")]
    Deflate(String),
    #[error("its level is larger than {} MiB, the limit for a level", MAX_LEVEL_BYTES >> 20)]
    TooLarge,
    #[error("its level is not UTF-8 text")]
    NotUtf8,
    #[error("{0}")]
    Level(Box<LevelError>),
}

impl LinkError {
    /// How to fix it, for the page's message.
    pub fn help(&self) -> &'static str {
        match self {
            LinkError::Level(_) => "ask for a new link: the level in it does not load",
            _ => "the link was cut or changed on its way: copy the whole link again, or ask for a new one (rigidlab link LEVEL)",
        }
    }
}

/// The level's text as a link's data: raw DEFLATE, then base64url without padding.
pub fn encode(text: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec(text.as_bytes(), LEVEL);
    data_encoding::BASE64URL_NOPAD.encode(&packed)
}

/// The level's text out of a link's data: the inverse of [`encode`], refusing what is not
/// base64url, what does not inflate, and more than a level's size limit once inflated.
pub fn decode(data: &str) -> Result<String, LinkError> {
    let data = data.trim();
    if data.is_empty() {
        return Err(LinkError::Missing);
    }
    let packed = data_encoding::BASE64URL_NOPAD
        .decode(data.as_bytes())
        .map_err(|e| LinkError::Base64 {
            // data-encoding counts from 0; a person counts from 1.
            position: e.position + 1,
            why: e.kind.to_string(),
        })?;
    let bytes =
        miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_LEVEL_BYTES as usize)
            .map_err(|e| match e.status {
                miniz_oxide::inflate::TINFLStatus::HasMoreOutput => LinkError::TooLarge,
                miniz_oxide::inflate::TINFLStatus::FailedCannotMakeProgress => {
                    LinkError::Deflate("the data ends before the level does".into())
                }
                s => LinkError::Deflate(format!("{s:?}")),
            })?;
    String::from_utf8(bytes).map_err(|_| LinkError::NotUtf8)
}

/// The link to `text` on the page at `base` (its address, e.g. `https://example.org/rigidlab/`),
/// with the level's file name.
pub fn url(base: &str, name: &str, text: &str) -> String {
    // A base with its own fragment would put ours after it, where no one reads it.
    let base = base.split('#').next().unwrap_or(base);
    format!(
        "{base}#{LEVEL_KEY}={}&{NAME_KEY}={}",
        encode(text),
        percent_encode(name)
    )
}

/// What a page address's fragment (`#level=...&name=...`, the `#` optional) carries: the level
/// data and the file name, if it carries a level at all.
pub fn fragment_parts(fragment: &str) -> Option<(String, String)> {
    let fragment = fragment.strip_prefix('#').unwrap_or(fragment);
    let mut data = None;
    let mut name = None;
    for pair in fragment.split('&') {
        match pair.split_once('=') {
            Some((LEVEL_KEY, v)) => data = Some(v.to_string()),
            Some((NAME_KEY, v)) => name = percent_decode(v),
            _ => {}
        }
    }
    let name = name
        .filter(|n| !n.is_empty() && !n.contains(['/', '\\']))
        .unwrap_or_else(|| DEFAULT_NAME.to_string());
    data.map(|d| (d, name))
}

/// The level a fragment carries, parsed and validated as a file of its name would be; `None`
/// when the fragment names no level.
pub fn open_fragment(fragment: &str) -> Option<Result<Scene, LinkError>> {
    open_fragment_as(fragment, &super::params::Pick::Nominal)
}

/// [`open_fragment`] as `pick` makes a level with parameters (a student's own numbers, by the
/// link's file name as `check --student` makes them by the file's).
pub fn open_fragment_as(
    fragment: &str,
    pick: &super::params::Pick,
) -> Option<Result<Scene, LinkError>> {
    let (data, name) = fragment_parts(fragment)?;
    Some(decode(&data).and_then(|text| {
        super::parse_variant(Path::new(&name), &text, pick)
            .map(|l| l.scene)
            .map_err(|e| LinkError::Level(Box::new(e)))
    }))
}

/// A file name in a URL: bytes other than `A-Z a-z 0-9 . - _` as `%XX`.
fn percent_encode(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'.' | b'-' | b'_' => (b as char).to_string(),
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// The inverse of [`percent_encode`] (any `%XX`); `None` for a broken escape or not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    const PENDULUM: &str = "// a comment is kept\nLevel(\n  title: \"Pendule, 60°\",\n  effects: [gravity, joints],\n  bodies: [(name: \"pivot\", kind: fixed), (name: \"bob\", shape: Circle(radius: 0.05), mass: 1.0, position: (0.5, 0.0))],\n  joints: [(name: \"rod\", kind: revolute, body1: \"pivot\", body2: \"bob\", anchor2: (-0.5, 0.0))],\n)\n";

    #[test]
    fn a_level_round_trips_byte_for_byte() {
        let data = encode(PENDULUM);
        assert!(
            data.bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_'),
            "{data}"
        );
        assert_eq!(decode(&data).unwrap(), PENDULUM);
    }

    #[test]
    fn a_url_opens_the_level_under_its_name() {
        let u = url(
            "https://example.org/rl/index.html#old",
            "my pendulum.ron",
            PENDULUM,
        );
        assert!(
            u.starts_with("https://example.org/rl/index.html#level="),
            "{u}"
        );
        assert!(u.ends_with("&name=my%20pendulum.ron"), "{u}");
        let fragment = &u[u.find('#').unwrap()..];
        let scene = open_fragment(fragment).unwrap().unwrap();
        assert_eq!(scene.file, Path::new("my pendulum.ron"));
        assert_eq!(scene.level.title, "Pendule, 60°");
    }

    #[test]
    fn a_fragment_without_a_level_is_none_and_a_name_may_not_be_a_path() {
        assert!(open_fragment("#play=1").is_none());
        assert!(open_fragment("").is_none());
        let (_, name) = fragment_parts("#level=x&name=..%2Fsecret.ron").unwrap();
        assert_eq!(name, DEFAULT_NAME);
    }

    #[test]
    fn bad_base64_names_the_character() {
        let mut data = encode(PENDULUM);
        data.replace_range(5..6, "*");
        match decode(&data) {
            Err(LinkError::Base64 { position, .. }) => assert_eq!(position, 6),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn damaged_or_cut_deflate_is_refused() {
        let packed = miniz_oxide::deflate::compress_to_vec(PENDULUM.as_bytes(), LEVEL);
        // Cut in half: the stream ends before its last block.
        let cut = data_encoding::BASE64URL_NOPAD.encode(&packed[..packed.len() / 2]);
        assert!(
            matches!(decode(&cut), Err(LinkError::Deflate(_))),
            "{:?}",
            decode(&cut)
        );
        // 0xff as the first byte: block type 3, which DEFLATE reserves (RFC 1951 3.2.3).
        let bad = data_encoding::BASE64URL_NOPAD.encode(&[0xff, 0x00, 0x12]);
        assert!(
            matches!(decode(&bad), Err(LinkError::Deflate(_))),
            "{:?}",
            decode(&bad)
        );
    }

    #[test]
    fn more_than_a_level_inflated_is_refused() {
        // 5 MiB of spaces deflate to a few KiB: over MAX_LEVEL_BYTES (4 MiB) once inflated.
        let big = " ".repeat(5 << 20);
        assert_eq!(decode(&encode(&big)), Err(LinkError::TooLarge));
    }

    #[test]
    fn text_that_is_not_a_level_is_its_level_error() {
        let r = open_fragment(&format!("#level={}", encode("hello"))).unwrap();
        match r {
            Err(LinkError::Level(e)) => {
                assert_eq!(e.file, Path::new(DEFAULT_NAME));
                assert_eq!(e.line, 1, "{e}");
            }
            other => panic!("{other:?}"),
        }
        let not_utf8 = data_encoding::BASE64URL_NOPAD
            .encode(&miniz_oxide::deflate::compress_to_vec(&[0xff, 0xfe], LEVEL));
        assert_eq!(decode(&not_utf8), Err(LinkError::NotUtf8));
    }
}

//! One entry of the reader registry ([`super::READERS`]): what a format contributes (its name,
//! extensions, magic-byte test and parser), and the channel choice every reader shares.
//!
//! A channel is one image of a file that stores several (height, amplitude, phase, …). A caller
//! names the channel it wants, or none for the file's height channel; an unknown name is a
//! [`ParseError::UnknownChannel`] listing the channels the file holds. A single-channel reader
//! reports its one channel, named by the reader or [`HEIGHT_CHANNEL`].

use super::{ParseError, Topography};

/// Name of the one channel of a file whose format stores only heights.
pub const HEIGHT_CHANNEL: &str = "height";

/// Parses a single-channel format.
pub type ParseFn = fn(&[u8]) -> Result<Topography, ParseError>;

/// Parses one channel of a multi-channel format: `None` asks for the height channel; the
/// returned [`Topography::channels`] lists every channel of the file.
pub type ChannelParseFn = fn(&[u8], Option<&str>) -> Result<Topography, ParseError>;

/// How a reader turns bytes into a [`Topography`].
#[derive(Debug, Clone, Copy)]
pub enum Parser {
    /// The format holds one channel.
    Single(ParseFn),
    /// The format may hold several channels, picked by name.
    Channels(ChannelParseFn),
}

/// A topography reader: one per format file, listed once in [`super::READERS`].
#[derive(Debug, Clone, Copy)]
pub struct Reader {
    /// Short lowercase name ("x3p", "sdf", …): the format column of `inspect` and the fuzz
    /// target's name.
    pub name: &'static str,
    /// What the format is, for users ("Zygo MetroPro `.dat`").
    pub description: &'static str,
    /// Lowercase file extensions, without the dot, tried when no magic bytes matched.
    pub extensions: &'static [&'static str],
    /// `true` when the first bytes of a file (at most 4 KiB) identify the format; `None` for a
    /// format without magic bytes (recognised by its extension only).
    pub magic: Option<fn(&[u8]) -> bool>,
    /// The parser.
    pub parser: Parser,
}

impl Reader {
    /// `true` when `head` (the first bytes of a file) carries this format's magic bytes.
    pub fn matches_magic(&self, head: &[u8]) -> bool {
        self.magic.is_some_and(|m| m(head))
    }

    /// `true` when the lowercase extension `ext` belongs to this format.
    pub fn matches_extension(&self, ext: &str) -> bool {
        self.extensions.contains(&ext)
    }

    /// Parses the whole file content with this reader, whatever its magic bytes say, reading
    /// the channel named `channel` (`None`: the height channel). The result names the channel
    /// read and lists every channel of the file; the scales the file states are plausible
    /// ([`super::plausible`]).
    pub fn parse(&self, bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
        let topography = self.parse_channel(bytes, channel)?;
        super::plausible::check(&topography)?;
        Ok(topography)
    }

    fn parse_channel(&self, bytes: &[u8], channel: Option<&str>) -> Result<Topography, ParseError> {
        match self.parser {
            Parser::Channels(parse) => parse(bytes, channel),
            Parser::Single(parse) => {
                let mut topography = parse(bytes)?;
                let name = topography
                    .channel
                    .get_or_insert_with(|| HEIGHT_CHANNEL.to_string())
                    .clone();
                if let Some(wanted) = channel {
                    if !same_channel(wanted, &name) {
                        return Err(unknown_channel(wanted, std::slice::from_ref(&name)));
                    }
                }
                topography.channels = vec![name];
                Ok(topography)
            }
        }
    }
}

/// Channel names compare without regard to ASCII case ("zsensor" finds "ZSensor").
pub(crate) fn same_channel(a: &str, b: &str) -> bool {
    a.eq_ignore_ascii_case(b)
}

/// The index in `names` of the channel `wanted`, or of the first of `defaults` the file holds
/// (else its first channel) when none is wanted.
pub(crate) fn pick_channel(
    names: &[String],
    wanted: Option<&str>,
    defaults: &[&str],
) -> Result<usize, ParseError> {
    let find = |w: &str| names.iter().position(|n| same_channel(n, w));
    match wanted {
        Some(w) => find(w).ok_or_else(|| unknown_channel(w, names)),
        None => defaults
            .iter()
            .find_map(|d| find(d))
            .or((!names.is_empty()).then_some(0))
            .ok_or_else(|| ParseError::malformed("the file holds no image channel")),
    }
}

/// The error for a channel name the file does not hold.
pub(crate) fn unknown_channel(wanted: &str, names: &[String]) -> ParseError {
    ParseError::UnknownChannel {
        wanted: wanted.to_string(),
        available: names.to_vec(),
    }
}

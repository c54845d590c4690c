//! The lines before the data: the version line, the label lines (`[KEYWORD] value`) and
//! the `TILT=` line that ends them.

use crate::scene::photometry::{Identity, Lm63Version};

/// What the first line says of the LM-63 version.
pub(super) enum Tag {
    /// A version line this reader knows.
    Known(Lm63Version),
    /// No version line: LM-63-1986.
    None,
    /// An LM-63 version line of a version this reader does not know.
    Unknown,
}

/// The version the first line (blanks ignored, any case) names.
pub(super) fn version(first_line: &str) -> Tag {
    let tag: String = first_line
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    match tag.as_str() {
        "IESNA91" => Tag::Known(Lm63Version::V1991),
        "IESNA:LM-63-1995" => Tag::Known(Lm63Version::V1995),
        "IESNA:LM-63-2002" => Tag::Known(Lm63Version::V2002),
        "IES:LM-63-2019" | "IESNA:LM-63-2019" => Tag::Known(Lm63Version::V2019),
        t if t.starts_with("IESNA:LM-63") || t.starts_with("IES:LM-63") => Tag::Unknown,
        _ => Tag::None,
    }
}

fn is_tilt_line(line: &str) -> bool {
    let t = line.trim_start().as_bytes();
    t.len() >= 5 && t[..5].eq_ignore_ascii_case(b"TILT=")
}

/// The keywords of the label lines from `start` up to the `TILT=` line, and that line's index.
pub(super) fn label(lines: &[(usize, &str)], start: usize) -> (Identity, Option<usize>) {
    let mut identity = Identity::default();
    let mut tilt = None;
    for (index, (_, line)) in lines.iter().enumerate().skip(start) {
        if is_tilt_line(line) {
            tilt = Some(index);
            break;
        }
        let line = line.trim();
        let keyword = line
            .strip_prefix('[')
            .and_then(|rest| rest.split_once(']'))
            .map(|(key, value)| (key.trim().to_ascii_uppercase(), value.trim().to_string()));
        match (keyword, identity.keywords.last_mut()) {
            // [MORE] continues the keyword before it.
            (Some((key, value)), Some(last)) if key == "MORE" => {
                last.1.push(' ');
                last.1.push_str(&value);
            }
            (Some(pair), _) => identity.keywords.push(pair),
            // LM-63-1986's free-form label, or a stray line: kept, under no keyword.
            (None, _) if !line.is_empty() => identity.keywords.push((String::new(), line.into())),
            (None, _) => {}
        }
    }
    let find = |key: &str| {
        identity
            .keywords
            .iter()
            .find(|(k, v)| k == key && !v.is_empty())
            .map(|(_, v)| v.clone())
    };
    identity.manufacturer = find("MANUFAC");
    identity.catalogue = find("LUMCAT");
    identity.luminaire = find("LUMINAIRE");
    identity.lamp = find("LAMP");
    identity.test = find("TEST");
    (identity, tilt)
}

//! A scene given as data — the scene file's schema as a TOML table built in memory (from a
//! Python dict, say) — written out as scene text with the place of every key remembered, so
//! that an error names the key's path (`medium[0].radius`) where a file's names its line and
//! column.

use std::ops::Range;
use toml::{Table, Value};

/// Scene text written from a table, and where each key of it went.
pub struct SceneText {
    /// The text, parsed as a scene file's.
    pub text: String,
    /// The bytes each key (and each table) occupies in `text`; nested places lie inside
    /// their table's.
    pub keys: Vec<KeyPlace>,
}

/// The bytes of a scene text that came from one key of the table.
#[derive(Clone, Debug)]
pub struct KeyPlace {
    /// The bytes.
    pub bytes: Range<usize>,
    /// The key's path from the top: `camera`, `medium[0]`, `medium[0].radius`.
    pub key: String,
}

impl SceneText {
    /// Writes `table` as scene text: its plain keys first, then its tables (`[camera]`),
    /// then its arrays of tables (`[[medium]]`), in each the keys in order; values deeper
    /// than a table's keys are written inline.
    pub fn write(table: &Table) -> SceneText {
        let mut w = SceneText {
            text: String::new(),
            keys: Vec::new(),
        };
        for (key, value) in table {
            if !matches!(value, Value::Table(_)) && tables(value).is_none() {
                w.entry(key, value, key.clone());
            }
        }
        for (key, value) in table {
            if let Value::Table(t) = value {
                w.table(&format!("[{}]", quoted(key)), t, key.clone());
            }
        }
        for (key, value) in table {
            for (i, t) in tables(value).into_iter().flatten().enumerate() {
                w.table(&format!("[[{}]]", quoted(key)), t, format!("{key}[{i}]"));
            }
        }
        w
    }

    /// The path of the innermost key whose bytes hold `offset` (see [`key_at`]).
    pub fn key_at(&self, offset: usize) -> Option<&str> {
        key_at(&self.keys, offset, self.text.len())
    }

    fn entry(&mut self, key: &str, value: &Value, path: String) {
        let start = self.text.len();
        self.text.push_str(&format!("{} = {value}\n", quoted(key)));
        self.place(start, path);
    }

    fn table(&mut self, header: &str, table: &Table, path: String) {
        let start = self.text.len();
        self.text.push_str(header);
        self.text.push('\n');
        for (key, value) in table {
            self.entry(key, value, format!("{path}.{key}"));
        }
        self.place(start, path);
    }

    fn place(&mut self, start: usize, key: String) {
        self.keys.push(KeyPlace {
            bytes: start..self.text.len(),
            key,
        });
    }
}

/// The path of the innermost of `keys` whose bytes hold `offset` in a text of `len` bytes
/// (an offset at or past the end counts as the last byte's; None for an empty text).
pub fn key_at(keys: &[KeyPlace], offset: usize, len: usize) -> Option<&str> {
    let offset = offset.min(len.saturating_sub(1));
    keys.iter()
        .filter(|k| k.bytes.contains(&offset))
        .min_by_key(|k| k.bytes.len())
        .map(|k| k.key.as_str())
}

/// The tables of a non-empty array holding only tables (a TOML array of tables).
fn tables(value: &Value) -> Option<impl Iterator<Item = &Table>> {
    match value {
        Value::Array(a) if !a.is_empty() && a.iter().all(Value::is_table) => {
            Some(a.iter().filter_map(Value::as_table))
        }
        _ => None,
    }
}

/// A key as TOML writes it: bare where it may be (letters, digits, `_` and `-`), else quoted.
fn quoted(key: &str) -> String {
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    match bare {
        true => key.to_string(),
        false => Value::String(key.to_string()).to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_text_parses_back_to_the_table_and_names_every_key() {
        let table: Table = toml::from_str(
            r#"
            ambient = "air"
            [camera]
            position = [0, 1, 2]
            [[medium]]
            name = "air"
            profile = "uniform"
            [[medium]]
            name = "odd \"name\""
            scattering = { albedo = 0.5 }
            "#,
        )
        .unwrap();
        let written = SceneText::write(&table);
        let back: Table = toml::from_str(&written.text).unwrap();
        assert_eq!(back, table);
        let at = |needle: &str| written.key_at(written.text.find(needle).unwrap());
        assert_eq!(at("ambient"), Some("ambient"));
        assert_eq!(at("[0, 1, 2]"), Some("camera.position"));
        assert_eq!(at("[[medium]]"), Some("medium[0]"));
        assert_eq!(at("\"uniform\""), Some("medium[0].profile"));
        assert_eq!(at("albedo"), Some("medium[1].scattering"));
        assert_eq!(
            written.key_at(written.text.len()),
            Some("medium[1].scattering")
        );
    }
}

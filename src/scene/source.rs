//! A parsed scene file: its text, its TOML table, and the span of every key path, so that
//! errors found later (by serde or by validation) point at the right line and column.

use std::collections::HashMap;
use std::ops::Range;
use std::sync::Arc;

use toml::de::{DeTable, DeValue};

use crate::diagnostics::{Diagnostic, Location, SourceFile};

/// One scene file, parsed.
#[derive(Debug)]
pub struct ParsedFile {
    /// The path as shown in messages.
    pub name: Arc<str>,
    /// The text, for line and column numbers.
    pub source: SourceFile,
    /// The document.
    pub table: toml::Table,
    key_spans: HashMap<String, Range<usize>>,
    value_spans: HashMap<String, Range<usize>>,
}

impl ParsedFile {
    /// Parses `text`; a syntax error becomes a diagnostic with its line and column.
    pub fn parse(name: &str, text: String) -> Result<Self, Diagnostic> {
        let name: Arc<str> = Arc::from(name);
        let source = SourceFile::new(name.to_string(), text);
        let mut key_spans = HashMap::new();
        let mut value_spans = HashMap::new();
        let syntax_error = |e: toml::de::Error| {
            let span = e.span().unwrap_or(0..0);
            let message = e.message().trim().to_string();
            Diagnostic::new(Location::new(&source, &name, span, ""), format!("TOML syntax error: {message}"))
        };
        let spanned = DeTable::parse(&source.text).map_err(syntax_error)?;
        index_table("", spanned.get_ref(), &mut key_spans, &mut value_spans);
        let table: toml::Table = toml::from_str(&source.text).map_err(syntax_error)?;
        Ok(Self { name, source, table, key_spans, value_spans })
    }

    /// The location of key path `key` (the key itself when it was written as a key, else
    /// its value; the nearest enclosing known path when neither is known).
    pub fn locate(&self, key: &str) -> Location {
        let mut probe = key.to_string();
        loop {
            if let Some(span) = self.key_spans.get(&probe).or_else(|| self.value_spans.get(&probe)) {
                return Location::new(&self.source, &self.name, span.clone(), key);
            }
            match probe.rfind(['.', '[']) {
                Some(i) => probe.truncate(i),
                None => return Location::new(&self.source, &self.name, 0..0, key),
            }
        }
    }

    /// The location of the value at `key`, used for type errors.
    pub fn locate_value(&self, key: &str) -> Location {
        match self.value_spans.get(key) {
            Some(span) => Location::new(&self.source, &self.name, span.clone(), key),
            None => self.locate(key),
        }
    }
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() { key.to_string() } else { format!("{prefix}.{key}") }
}

fn index_table(
    prefix: &str,
    table: &DeTable<'_>,
    keys: &mut HashMap<String, Range<usize>>,
    values: &mut HashMap<String, Range<usize>>,
) {
    for (key, value) in table.iter() {
        let path = join(prefix, key.get_ref());
        keys.insert(path.clone(), key.span());
        values.insert(path.clone(), value.span());
        index_value(&path, value.get_ref(), keys, values);
    }
}

fn index_value(
    path: &str,
    value: &DeValue<'_>,
    keys: &mut HashMap<String, Range<usize>>,
    values: &mut HashMap<String, Range<usize>>,
) {
    match value {
        DeValue::Table(t) => index_table(path, t, keys, values),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                let p = format!("{path}[{i}]");
                values.insert(p.clone(), item.span());
                index_value(&p, item.get_ref(), keys, values);
            }
        }
        _ => {}
    }
}

/// The key path of a serde_path_to_error path, in the `a.b[2].c` form used by [`ParsedFile`].
pub fn path_string(prefix: &str, path: &serde_path_to_error::Path) -> String {
    let mut out = prefix.to_string();
    for segment in path.iter() {
        match segment {
            serde_path_to_error::Segment::Seq { index } => out.push_str(&format!("[{index}]")),
            serde_path_to_error::Segment::Map { key } | serde_path_to_error::Segment::Enum { variant: key } => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(key);
            }
            serde_path_to_error::Segment::Unknown => {}
        }
    }
    out
}

/// Deserialises `value` (found at key path `prefix` of `file`) into `T`; an error names the
/// exact key, its line and column, and the nearest valid field name for a typo.
pub fn deserialize_at<T: serde::de::DeserializeOwned>(
    file: &ParsedFile,
    prefix: &str,
    value: toml::Value,
) -> Result<T, Diagnostic> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = path_string(prefix, e.path());
        let message = e.inner().message().trim().to_string();
        serde_diagnostic(file, &path, &message)
    })
}

/// A diagnostic for a serde `message` about key path `path`.
pub fn serde_diagnostic(file: &ParsedFile, path: &str, message: &str) -> Diagnostic {
    if let Some((field, expected)) = crate::diagnostics::parse_unknown_field(message) {
        // serde_path_to_error already ends the path with the unknown key; other callers don't.
        let key =
            if path == field || path.ends_with(&format!(".{field}")) { path.to_string() } else { join(path, &field) };
        let diagnostic = Diagnostic::new(file.locate(&key), format!("unknown key `{field}`"));
        let with_help = diagnostic.clone().suggest(&field, expected.iter().map(String::as_str));
        return if with_help.help.is_some() || expected.is_empty() {
            with_help
        } else {
            diagnostic.with_help(format!("valid keys here: {}", expected.join(", ")))
        };
    }
    Diagnostic::new(file.locate_value(path), message.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_nested_keys_and_array_elements() {
        let text =
            "[render]\nwidth = 10\n\n[[object]]\nshape = \"sphere\"\n\n[[object]]\nshape = \"box\"\nradius = 2\n";
        let f = ParsedFile::parse("s.toml", text.to_string()).unwrap();
        let l = f.locate("render.width");
        assert_eq!((l.line, l.column), (2, 1));
        let l = f.locate("object[1].radius");
        assert_eq!((l.line, l.column), (9, 1));
        let l = f.locate("object[1].nothing");
        assert_eq!(l.line, 7, "falls back to the enclosing table");
    }

    #[test]
    fn syntax_error_has_a_line() {
        let e = ParsedFile::parse("s.toml", "a = 1\nb = \n".to_string()).unwrap_err();
        assert_eq!(e.location.line, 2);
        assert!(e.message.contains("syntax"), "{e}");
    }
}

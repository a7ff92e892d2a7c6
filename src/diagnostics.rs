//! Scene diagnostics: every problem in a scene names the file, line, column and key path,
//! says what is wrong and, where it can, suggests the nearest valid name. A problem is an
//! error (the scene cannot be rendered; loading returns a [`SceneError`]) or a warning
//! (something was skipped or approximated; the loaded scene carries it in
//! [`crate::world::Scene::warnings`]). The library never prints: the caller shows them.

use std::fmt;
use std::ops::Range;
use std::sync::Arc;

/// A scene source file kept for turning byte offsets into line and column numbers.
#[derive(Debug)]
pub struct SourceFile {
    /// The path as the user wrote it (or `<built-in>/...` for embedded scenes).
    pub path: String,
    /// The file's text.
    pub text: String,
    /// Byte offset of every line's start, so a lookup costs a binary search, not a scan
    /// of the text (a scene with 100,000 objects asks for hundreds of thousands).
    line_starts: Vec<usize>,
}

impl SourceFile {
    /// The file at `path` holding `text`.
    pub fn new(path: impl Into<String>, text: String) -> Self {
        let line_starts = std::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect();
        Self { path: path.into(), text, line_starts }
    }

    /// 1-based line and column of byte `offset` (columns count characters).
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.line_starts.partition_point(|&start| start <= offset);
        let line_start = self.line_starts[line - 1];
        let col = self.text[line_start..offset].chars().count() + 1;
        (line, col)
    }
}

/// Where something in a scene came from: file, line, column and key path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The scene file.
    pub file: Arc<str>,
    /// 1-based line (0 when unknown).
    pub line: usize,
    /// 1-based column (0 when unknown).
    pub column: usize,
    /// Dotted key path, such as `object[2].radius`.
    pub key: String,
}

impl Location {
    /// The location of byte range `span` of `source`, for key path `key`.
    pub fn new(source: &SourceFile, file: &Arc<str>, span: Range<usize>, key: impl Into<String>) -> Self {
        let (line, column) = source.line_col(span.start);
        Self { file: file.clone(), line, column, key: key.into() }
    }

    /// A location with no line information (command-line options, files that failed to open).
    pub fn file_only(file: impl Into<Arc<str>>, key: impl Into<String>) -> Self {
        Self { file: file.into(), line: 0, column: 0, key: key.into() }
    }

    /// The same place, pointing at a sub-key.
    pub fn child(&self, key: &str) -> Self {
        let key = if self.key.is_empty() { key.to_string() } else { format!("{}.{key}", self.key) };
        Self { key, ..self.clone() }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = sanitize(&crate::files::shown(&self.file));
        if self.line > 0 { write!(f, "{file}:{}:{}", self.line, self.column) } else { write!(f, "{file}") }
    }
}

/// Whether a [`Diagnostic`] stops the scene from rendering.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Severity {
    /// The scene cannot be rendered as written.
    #[default]
    Error,
    /// Something was skipped or approximated; the scene still renders.
    Warning,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
        })
    }
}

/// One problem in a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Where it is.
    pub location: Location,
    /// What is wrong.
    pub message: String,
    /// What to do about it, such as "did you mean `radius`?".
    pub help: Option<String>,
}

impl Diagnostic {
    /// An error at `location`.
    pub fn new(location: Location, message: impl Into<String>) -> Self {
        Self { severity: Severity::Error, location, message: message.into(), help: None }
    }

    /// A warning at `location`.
    pub fn warning(location: Location, message: impl Into<String>) -> Self {
        Self { severity: Severity::Warning, ..Self::new(location, message) }
    }

    /// The same diagnostic with a hint.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Adds "did you mean `x`?" when one of `candidates` is close to `wrong`.
    pub fn suggest<'a>(self, wrong: &str, candidates: impl IntoIterator<Item = &'a str>) -> Self {
        match nearest_name(wrong, candidates) {
            Some(name) => self.with_help(format!("did you mean `{name}`?")),
            None => self,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.location, self.severity)?;
        if !self.location.key.is_empty() {
            write!(f, " in {}", sanitize(&format!("`{}`", self.location.key)))?;
        }
        write!(f, ": {}", sanitize(&self.message))?;
        if let Some(help) = &self.help {
            write!(f, "\n  help: {}", sanitize(help))?;
        }
        Ok(())
    }
}

/// Longest message shown, in characters (a longer one is cut, marked with `...`).
pub const MAX_MESSAGE_CHARS: usize = 1000;

/// `text` safe to print: control characters (terminal escapes) become `?`, every quoted
/// part (between backticks or double quotes: names, keys, string values that a parser
/// repeats) longer than [`crate::files::MAX_SHOWN_CHARS`] is shortened to its start and
/// end, a number written out in full (an `f64` formatted with `{}`: 1e300 has 301 digits) is
/// rewritten as [`shown_number`] writes it, and the whole is cut at [`MAX_MESSAGE_CHARS`].
/// So a message never repeats more of what a file holds than a short name.
pub fn sanitize(text: &str) -> String {
    let text = &*shorten_long_numbers(text);
    let limit = crate::files::MAX_SHOWN_CHARS;
    let mut out = String::with_capacity(text.len().min(MAX_MESSAGE_CHARS + 3));
    let mut quoted: Option<(char, String)> = None;
    let flush = |out: &mut String, quote: char, inner: &str, closed: bool| {
        out.push(quote);
        let n = inner.chars().count();
        if n > limit {
            let head: String = inner.chars().take(limit / 2 - 2).collect();
            let tail: String = inner.chars().skip(n - (limit / 2 - 2)).collect();
            out.push_str(&format!("{head}...{tail}"));
        } else {
            out.push_str(inner);
        }
        if closed {
            out.push(quote);
        }
    };
    for c in text.chars() {
        let c = if c.is_control() && c != '\n' { '?' } else { c };
        match &mut quoted {
            Some((quote, inner)) if c == *quote => {
                let (quote, inner) = (*quote, std::mem::take(inner));
                flush(&mut out, quote, &inner, true);
                quoted = None;
            }
            Some((_, inner)) => inner.push(c),
            None if c == '`' || c == '"' => quoted = Some((c, String::new())),
            None => out.push(c),
        }
        if out.chars().count() > MAX_MESSAGE_CHARS {
            break;
        }
    }
    if let Some((quote, inner)) = quoted {
        flush(&mut out, quote, &inner, false);
    }
    if out.chars().count() > MAX_MESSAGE_CHARS {
        out = out.chars().take(MAX_MESSAGE_CHARS).collect::<String>() + "...";
    }
    out
}

/// One or more problems that stop a scene from loading (errors, never warnings).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The problems, in file order.
    pub diagnostics: Vec<Diagnostic>,
}

impl SceneError {
    /// An error holding one diagnostic.
    pub fn single(diagnostic: Diagnostic) -> Self {
        Self { diagnostics: vec![diagnostic] }
    }
}

impl From<Diagnostic> for SceneError {
    fn from(d: Diagnostic) -> Self {
        Self::single(d)
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.diagnostics.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneError {}

/// Longest run of digits (and decimal point) a message shows as written: an f64 needs at
/// most 17 significant digits, so a longer number is one formatted out in full.
const MAX_NUMBER_CHARS: usize = 24;

/// `text` with every number longer than [`MAX_NUMBER_CHARS`] (digits and a decimal point,
/// not part of a word or a path) rewritten by [`shown_number`].
fn shorten_long_numbers(text: &str) -> std::borrow::Cow<'_, str> {
    let in_number = |c: char| c.is_ascii_digit() || c == '.';
    let in_word = |c: char| c.is_alphanumeric() || c == '_' || c == '/' || c == '\\';
    let mut out = String::new();
    let mut copied = 0;
    let mut chars = text.char_indices().peekable();
    let mut previous: Option<char> = None;
    while let Some((start, c)) = chars.next() {
        if !c.is_ascii_digit() || previous.is_some_and(|p| in_word(p) || p == '.') {
            previous = Some(c);
            continue;
        }
        let mut end = start + 1;
        while let Some(&(i, d)) = chars.peek().filter(|(_, d)| in_number(*d)) {
            end = i + d.len_utf8();
            chars.next();
        }
        previous = text[..end].chars().next_back();
        let followed_by_word = chars.peek().is_some_and(|&(_, d)| in_word(d));
        let run = &text[start..end];
        if run.len() > MAX_NUMBER_CHARS
            && !followed_by_word
            && let Ok(v) = run.parse::<f64>()
        {
            out.push_str(&text[copied..start]);
            out.push_str(&shown_number(v));
            copied = end;
        }
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(&text[copied..]);
    std::borrow::Cow::Owned(out)
}

/// A number as a message shows it: in scientific notation when very large or very small
/// (`1e300`, not three hundred digits), else as written.
pub fn shown_number(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-6..1e9).contains(&v.abs()) { format!("{v:e}") } else { format!("{v}") }
}

/// The candidate closest to `wrong` by edit distance, if it is close enough to be a typo.
pub fn nearest_name<'a>(wrong: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::damerau_levenshtein(&wrong.to_lowercase(), &c.to_lowercase()), c))
        .filter(|(d, c)| *d <= (c.len().max(wrong.len()) / 3).max(2))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Field names listed in a serde "unknown field `x`, expected one of `a`, `b`" message:
/// the unknown field and the expected names. serde reports an unknown field only as this
/// text (`serde::de::Error::unknown_field` builds it; toml keeps no typed form), so this is
/// the one place that reads an error message, and it reads serde's fixed wording, not ours.
pub fn parse_unknown_field(message: &str) -> Option<(String, Vec<String>)> {
    let rest = message.strip_prefix("unknown field `")?;
    let end = rest.find('`')?;
    let field = rest[..end].to_string();
    let expected = rest[end + 1..].split('`').skip(1).step_by(2).map(str::to_string).collect();
    Some((field, expected))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shown_short() {
        assert_eq!(shown_number(1e300), "1e300");
        assert_eq!(shown_number(-2.5e-12), "-2.5e-12");
        assert_eq!(shown_number(0.0), "0");
        assert_eq!(shown_number(-1.5), "-1.5");
        assert_eq!(shown_number(180.0), "180");
        assert_eq!(shown_number(f64::NAN), "NaN");
    }

    /// What a parser repeats from a file (a 10 MB string value, a long key, a terminal
    /// escape) is shortened in the message, never echoed whole.
    #[test]
    fn messages_do_not_echo_file_contents() {
        let secret = "s".repeat(10_000);
        let shown = sanitize(&format!("invalid type: string \"{secret}\", expected u32"));
        assert!(shown.len() < 200, "{shown}");
        assert!(shown.starts_with("invalid type: string \"sss") && shown.ends_with("sss\", expected u32"));
        assert_eq!(sanitize("unknown shape `sphear`"), "unknown shape `sphear`");
        assert_eq!(sanitize("a\u{1b}[31mred"), "a?[31mred");
        // Numbers formatted in full are shown as `shown_number` shows them; short numbers,
        // and digits in names and paths, as written.
        let huge = format!("must be at most 10, got {} and {}", 1e300, -1e-300);
        assert_eq!(sanitize(&huge), "must be at most 10, got 1e300 and -1e-300");
        assert_eq!(sanitize("got 0.30000000000000004 in [1, 2.5]"), "got 0.30000000000000004 in [1, 2.5]");
        let name = format!("file f{0}.toml and dir/{0}/x", "1".repeat(40));
        assert_eq!(sanitize(&name), name);
        assert!(sanitize(&"x".repeat(5000)).chars().count() <= MAX_MESSAGE_CHARS + 3);
        let d = Diagnostic::new(Location::file_only("a.toml", "k".repeat(500)), format!("unknown shape `{secret}`"));
        assert!(d.to_string().len() < 300, "{d}");
    }

    #[test]
    fn line_and_column() {
        let s = SourceFile::new("a.toml", "a = 1\nbé = 2\n".into());
        assert_eq!(s.line_col(0), (1, 1));
        assert_eq!(s.line_col(6), (2, 1));
        assert_eq!(s.line_col(0), (1, 1));
        assert_eq!(s.line_col(6), (2, 1));
        assert_eq!(s.line_col(9), (2, 3));
    }

    #[test]
    fn suggestions() {
        assert_eq!(nearest_name("radus", ["radius", "center"]), Some("radius"));
        assert_eq!(nearest_name("colour", ["color", "ambient"]), Some("color"));
        assert_eq!(nearest_name("zzzzzz", ["radius", "center"]), None);
    }

    #[test]
    fn severity_is_shown_with_the_location_and_key() {
        let location = Location { file: "s.toml".into(), line: 3, column: 7, key: "object[0].file".into() };
        let warning = Diagnostic::warning(location.clone(), "`a.gltf`: animations are ignored");
        assert_eq!(warning.to_string(), "s.toml:3:7: warning in `object[0].file`: `a.gltf`: animations are ignored");
        let error = Diagnostic::new(location, "no").with_help("yes");
        assert_eq!(error.severity, Severity::Error);
        assert_eq!(error.to_string(), "s.toml:3:7: error in `object[0].file`: no\n  help: yes");
    }

    #[test]
    fn unknown_field_message() {
        let (f, e) = parse_unknown_field("unknown field `radus`, expected `center` or `radius`").unwrap();
        assert_eq!(f, "radus");
        assert_eq!(e, vec!["center", "radius"]);
    }
}

//! Why a stream holds no sample, in words that name the fix: a line quoted, what was found in it and
//! what is missing, and the change to the sketch that would do; never a cause that is not so (a
//! wrong baud rate is named only for bytes that are not text, by [`super::checked_text`] and the
//! live session's silence).

use super::line::{fields, Fields, Words};
use crate::limits::NOT_TEXT_SHARE;

/// The longest part of a line quoted in a message.
const QUOTED_CHARS: usize = 60;

/// Why none of `lines` holds a sample: the stream's refusal in words.
pub(super) fn why_no_samples(lines: &[&str]) -> String {
    let parsed: Vec<(usize, &str, Result<Fields, Words>)> =
        lines.iter().enumerate().filter(|(_, l)| !l.trim().is_empty()).map(|(i, l)| (i + 1, *l, fields(l))).collect();
    // NOTE: reversed, so that of lines with as many values the first is quoted.
    let most = parsed
        .iter()
        .rev()
        .filter_map(|(n, l, f)| f.as_ref().ok().map(|f| (n, l, f)))
        .max_by_key(|(_, _, f)| f.values.len());
    if let Some((n, line, found)) = most {
        return too_few(*n, line, found);
    }
    let numbered = parsed.iter().find(|(_, l, _)| l.chars().any(|c| c.is_ascii_digit()));
    match (numbered, parsed.first()) {
        (Some((n, line, _)), _) => format!(
            "line {n} {} has numbers among words that label none of them: a log or another program's text, not a \
             sensor's stream; a sketch's line reads as `ax=0.01 ay=-0.02 az=0.99` or `0.01,-0.02,0.99`",
            quote(line)
        ),
        (None, Some((n, line, _))) => format!(
            "they hold words and no number (line {n}: {}): another program's text or a log with no sensor, not a \
             sensor's stream",
            quote(line)
        ),
        (None, None) => "every line is empty: the sketch prints no values (look at its Serial.print calls)".to_owned(),
    }
}

/// Why lines that are text hold no sample, when they are text (a wrong baud rate garbles the bytes
/// into U+FFFD and control characters: none when they are not text).
pub fn text_without_samples(lines: &[&str]) -> Option<String> {
    let chars: usize = lines.iter().map(|l| l.chars().count()).sum();
    let garbled = |c: char| c == char::REPLACEMENT_CHARACTER || (c.is_control() && !matches!(c, '\t' | '\u{1b}'));
    let not_text: usize = lines.iter().map(|l| l.chars().filter(|&c| garbled(c)).count()).sum();
    (chars > 0 && (not_text as f64) <= NOT_TEXT_SHARE * chars as f64).then(|| why_no_samples(lines))
}

/// A line that holds values, but fewer than the accelerometer's three.
fn too_few(n: usize, line: &str, found: &Fields) -> String {
    let count = found.values.len();
    let labels = match found.labels.is_empty() {
        true => String::new(),
        false => format!(" ({})", found.labels.join(", ")),
    };
    format!(
        "line {n} {} holds {count} value{}{labels} and no line holds three: the accelerometer's x, y and z are \
         needed on each line (or over a few lines, in the same order each time); have the sketch print all three, \
         e.g. `Serial.print(ax); Serial.print(','); Serial.print(ay); Serial.print(','); Serial.println(az);`",
        quote(line),
        if count == 1 { "" } else { "s" }
    )
}

/// A line as a message quotes it: in backticks, cut short when long.
pub(super) fn quote(line: &str) -> String {
    let line = line.trim();
    match line.chars().count() > QUOTED_CHARS {
        true => format!("`{}...`", line.chars().take(QUOTED_CHARS).collect::<String>()),
        false => format!("`{line}`"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each refused kind: the lines, and what its message must say (the cause and the fix).
    #[test]
    fn each_refused_kind_names_what_it_is_and_the_fix() {
        let cases: [(&[&str], &[&str]); 5] = [
            (&["12,34", "13,35", "12,36"], &["line 1 `12,34` holds 2 values", "Serial.println(az)"]),
            (&["temp=21.5", "temp=21.6"], &["holds 1 value (temp)", "x, y and z"]),
            (
                &["2026-11-28 10:00:01 GET /index.html 200 1234", "2026-11-28 10:00:02 GET /a.css 200 99"],
                &["line 1 `2026-11-28 10:00:01 GET", "not a sensor's stream", "`ax=0.01 ay=-0.02 az=0.99`"],
            ),
            (&["fn main() {", "    println!(\"hello\");", "}"], &["words and no number", "another program's text"]),
            (&["", "  "], &["every line is empty"]),
        ];
        for (lines, wanted) in cases {
            let said = why_no_samples(lines);
            for words in wanted {
                assert!(said.contains(words), "{lines:?}: {said}");
            }
            assert!(!said.contains("baud"), "{said}");
        }
        let garbled = super::super::text_of(&[0xf8, 0x80, 0x66, 0xfe, 0x00, 0x1c, 0x78, 0x98, 0x9e, 0x06, 0xe0]);
        assert_eq!(text_without_samples(&[&garbled, &garbled]), None, "bytes that are not text: the baud rate");
        assert!(text_without_samples(&["12,34"]).is_some_and(|why| why.contains("holds 2 values")));
    }
}

//! Telling an empty, a foreign and a truncated file apart before the DXF reader sees them, so
//! each gets its own message (the reader itself accepts an empty or cut-off file as an empty
//! drawing).

use super::DxfImportError;

/// Sentinel at the start of a binary DXF.
const BINARY_SENTINEL: &[u8] = b"AutoCAD Binary DXF";

/// Checks that `bytes` are a whole ASCII DXF (or a binary one, left to the reader).
///
/// # Errors
/// [`DxfImportError::Empty`], [`DxfImportError::NotDxf`] or [`DxfImportError::Truncated`].
pub(super) fn sniff(bytes: &[u8]) -> Result<(), DxfImportError> {
    if bytes.is_empty() {
        return Err(DxfImportError::Empty);
    }
    if bytes.starts_with(BINARY_SENTINEL) {
        return Ok(());
    }
    let text = String::from_utf8_lossy(bytes);
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let lines: Vec<&str> = text.lines().map(str::trim).collect();
    // Group pairs: code line, value line. Comments (999) may come first.
    let mut at = lines.iter().position(|l| !l.is_empty()).unwrap_or(0);
    while lines.get(at) == Some(&"999") {
        at += 2;
    }
    let starts_right = lines.get(at).and_then(|c| c.parse::<i32>().ok()) == Some(0)
        && lines
            .get(at + 1)
            .is_some_and(|v| v.eq_ignore_ascii_case("SECTION"));
    if !starts_right {
        let start: String = text.trim_start().chars().take(40).collect();
        return Err(DxfImportError::NotDxf { start });
    }
    let mut section = String::from("the file header");
    let mut i = at;
    while i + 1 < lines.len() {
        let (code, value) = (lines[i], lines[i + 1]);
        if code == "0" && value.eq_ignore_ascii_case("EOF") {
            return Ok(());
        }
        if code == "0" && value.eq_ignore_ascii_case("SECTION") {
            if let Some(name) = lines.get(i + 3).filter(|_| lines.get(i + 2) == Some(&"2")) {
                section = format!("the {name} section");
            }
        } else if code == "0" && value.eq_ignore_ascii_case("ENDSEC") {
            section = format!("after {}", section.trim_start_matches("after "));
        }
        i += 2;
    }
    Err(DxfImportError::Truncated {
        bytes: bytes.len(),
        line: lines.len(),
        section,
    })
}

/// Whether an ASCII DXF sets the header variable `name` (group 9 followed by the name; the
/// name inside a TEXT does not count).
pub(super) fn has_header_variable(bytes: &[u8], name: &str) -> bool {
    let text = String::from_utf8_lossy(bytes);
    let mut lines = text.lines().map(str::trim);
    let mut previous = lines.next();
    for line in lines {
        if previous == Some("9") && line == name {
            return true;
        }
        previous = Some(line);
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tells_empty_foreign_and_truncated_files_apart() {
        assert!(matches!(sniff(b""), Err(DxfImportError::Empty)));
        let err = sniff(b"%PDF-1.7\n...").unwrap_err();
        assert!(err.to_string().contains("starts with \"%PDF-1.7"), "{err}");
        let whole = "  0\nSECTION\n  2\nENTITIES\n  0\nLINE\n  8\n0\n  0\nENDSEC\n  0\nEOF\n";
        assert!(sniff(whole.as_bytes()).is_ok());
        let cut = &whole[..whole.find("  0\nENDSEC").unwrap()];
        let err = sniff(cut.as_bytes()).unwrap_err();
        assert!(
            matches!(&err, DxfImportError::Truncated { section, line: 8, .. } if section == "the ENTITIES section"),
            "{err}"
        );
        assert!(sniff(b"999\nmade by hand\n0\nSECTION\n0\nEOF\n").is_ok());
        assert!(has_header_variable(
            b"  9\n$INSUNITS\n 70\n4\n",
            "$INSUNITS"
        ));
        assert!(!has_header_variable(b"  1\nunits $INSUNITS\n", "$INSUNITS"));
    }
}

//! The standard streams as a stranger's shell hands them over: a full disk
//! (`2>/dev/full`) or a reader gone (`2>&1 | head -2`). Messages on stderr
//! never stop the work. (A stream closed with `>&-` is opened on `/dev/null` by
//! Rust's runtime before `main`, so no file of ours takes its number; output
//! to it is lost as with `> /dev/null`, which it cannot be told apart from:
//! Python's `subprocess.DEVNULL` opens `/dev/null` the same way.)

use std::io::Write;

/// Past a file-size limit (`ulimit -f`) a write fails with "File too large",
/// and the temporary file is removed with a one-line error, instead of the
/// kernel's SIGXFSZ ending the process silently with a half file left. Called
/// first in `main`, before any thread starts.
pub fn write_errors_not_signals() {
    // SAFETY: setting a signal to be ignored has no preconditions; no other
    // thread exists yet to race on the disposition.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// `line` on stderr; a stderr that cannot be written loses it, and nothing else.
pub fn say(line: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err
        .write_all(line.as_bytes())
        .and_then(|()| err.write_all(b"\n"));
}

/// `text` with its control characters written as escapes (`\u{1b}`, `\n`): a
/// name from a model file or a path must not move the terminal's cursor, set
/// its title or break a message's one line.
pub fn printable(text: &str) -> String {
    let mut shown = String::with_capacity(text.len());
    for c in text.chars() {
        match c.is_control() {
            true => shown.extend(c.escape_default()),
            false => shown.push(c),
        }
    }
    shown
}

/// [`say`] with `format!`'s arguments.
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::app::streams::say(&format!($($arg)*))
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_and_letters_kept() {
        assert_eq!(
            printable("usemtl \u{1b}]0;TITLE\u{7}\rX é\tb\n"),
            "usemtl \\u{1b}]0;TITLE\\u{7}\\rX é\\tb\\n"
        );
        assert_eq!(printable("plain name.obj"), "plain name.obj");
    }
}

//! The standard streams as a stranger's shell hands them over: closed (`>&-`),
//! a full disk (`2>/dev/full`) or a reader gone (`2>&1 | head -2`). Messages on
//! stderr never stop the work, and output meant for a closed stdout fails
//! rather than landing in a file this program opened.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// Opens `/dev/null` on each standard stream the caller closed, so that no file
/// opened later takes its number (a model, or a temporary image, would get
/// stderr's messages), and remembers a closed stdout. Called first thing.
///
/// Rust's runtime already does the opening before `main`, read-write; a shell
/// sends output to `/dev/null` write-only (`> /dev/null`). So a stdout that is
/// `/dev/null` open for reading and writing was closed.
pub fn guard() {
    if null_opened_by_the_runtime(libc::STDOUT_FILENO) {
        STDOUT_CLOSED.store(true, Ordering::Relaxed);
    }
    for fd in 0..3 {
        // SAFETY: F_GETFD only reads the descriptor's flags.
        if unsafe { libc::fcntl(fd, libc::F_GETFD) } != -1 {
            continue;
        }
        if fd == libc::STDOUT_FILENO {
            STDOUT_CLOSED.store(true, Ordering::Relaxed);
        }
        // The lowest free number: `fd`, as the ones below it are open.
        let null = std::fs::OpenOptions::new()
            .read(fd == libc::STDIN_FILENO)
            .write(fd != libc::STDIN_FILENO)
            .open("/dev/null");
        if let Ok(null) = null {
            let opened = std::os::fd::IntoRawFd::into_raw_fd(null);
            if opened != fd {
                // SAFETY: `opened` is ours alone, just opened.
                unsafe { libc::close(opened) };
            }
        }
    }
}

/// Whether `fd` is `/dev/null` open for reading and writing.
fn null_opened_by_the_runtime(fd: i32) -> bool {
    use std::os::unix::fs::MetadataExt;
    // SAFETY: F_GETFL and fstat only read the descriptor's state into `stat`.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags == -1 || flags & libc::O_ACCMODE != libc::O_RDWR {
        return false;
    }
    let mut stat = std::mem::MaybeUninit::<libc::stat>::uninit();
    if unsafe { libc::fstat(fd, stat.as_mut_ptr()) } != 0 {
        return false;
    }
    // SAFETY: fstat succeeded, so it filled `stat`.
    let stat = unsafe { stat.assume_init() };
    let null = std::fs::metadata("/dev/null");
    stat.st_mode & libc::S_IFMT == libc::S_IFCHR && null.is_ok_and(|n| n.rdev() == stat.st_rdev)
}

/// Whether stdout was closed when the program started ([`guard`]).
pub fn stdout_closed() -> bool {
    STDOUT_CLOSED.load(Ordering::Relaxed)
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
    text.chars()
        .map(|c| match c.is_control() {
            true => c.escape_default().to_string(),
            false => c.to_string(),
        })
        .collect()
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

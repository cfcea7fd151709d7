//! CRLF line ends read as LF, so the CSV reader sees one line end.

use std::io::Read;

/// A reader that passes its input on with every CRLF line end as LF (a lone CR stays), and
/// ends it with an LF if it does not end with one.
pub(super) struct CrlfAsLf<R> {
    inner: R,
    buf: Box<[u8]>,
    /// The unread part of `buf` is `start..end`.
    start: usize,
    end: usize,
    eof: bool,
    /// The last byte passed on.
    last: Option<u8>,
}

impl<R: Read> CrlfAsLf<R> {
    pub(super) fn new(inner: R) -> Self {
        CrlfAsLf {
            inner,
            buf: vec![0; 1 << 16].into_boxed_slice(),
            start: 0,
            end: 0,
            eof: false,
            last: None,
        }
    }

    /// Whether more input is needed before a byte can be passed on: none is left, or only a
    /// CR whose next byte is still to come.
    fn needs_input(&self) -> bool {
        match self.end - self.start {
            0 => !self.eof,
            1 => !self.eof && self.buf[self.start] == b'\r',
            _ => false,
        }
    }
}

impl<R: Read> Read for CrlfAsLf<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        while self.needs_input() {
            self.buf.copy_within(self.start..self.end, 0);
            self.end -= self.start;
            self.start = 0;
            let n = self.inner.read(&mut self.buf[self.end..])?;
            self.eof = n == 0;
            self.end += n;
        }
        let mut written = 0;
        while written < out.len() && self.start < self.end {
            let b = self.buf[self.start];
            if b == b'\r' {
                match self.buf[self.start + 1..self.end].first() {
                    Some(b'\n') => {
                        self.start += 1;
                        continue;
                    }
                    None if !self.eof => break,
                    _ => {}
                }
            }
            out[written] = b;
            written += 1;
            self.start += 1;
        }
        if written == 0 && self.eof && !out.is_empty() && self.last.is_some_and(|b| b != b'\n') {
            out[0] = b'\n';
            written = 1;
        }
        if written > 0 {
            self.last = Some(out[written - 1]);
        }
        Ok(written)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that hands out at most `.1` bytes per call: with 1 every CR meets the end
    /// of a read; with more, a CR also ends a read after other bytes ("a,b\r\n" in reads
    /// of 3: "a,b", "\r\n..."; in reads of 2: "a,", "b\r", "\n...").
    struct Chunks<'a>(&'a [u8], usize);

    impl Read for Chunks<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(out.len()).min(self.1);
            out[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    fn through(input: &[u8], in_len: usize, out_len: usize) -> Vec<u8> {
        let mut r = CrlfAsLf::new(Chunks(input, in_len));
        let mut all = Vec::new();
        let mut buf = vec![0; out_len];
        loop {
            let n = r.read(&mut buf).unwrap();
            if n == 0 {
                return all;
            }
            all.extend_from_slice(&buf[..n]);
        }
    }

    /// CRLF becomes LF wherever the reads (of the input, and of the output) split it, a lone
    /// CR stays, and the text ends with one LF (added only when missing).
    #[test]
    fn crlf_reads_as_lf() {
        for in_len in [1, 2, 3, 5, 64] {
            for out_len in [1, 2, 7] {
                let through = |input: &[u8]| through(input, in_len, out_len);
                assert_eq!(through(b"a,b\r\n1,2\r\n"), b"a,b\n1,2\n");
                assert_eq!(through(b"a\rb\r\n\r\nc"), b"a\rb\n\nc\n");
                assert_eq!(through(b"x\r"), b"x\r\n");
                assert_eq!(through(b""), b"");
            }
        }
    }
}

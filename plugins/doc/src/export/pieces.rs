//! Writing a large output made in pieces on all cores (issue 36, item 2):
//! the pieces are made a few at a time in parallel while the ones made
//! before are written, in order, so the cores make bytes while the disk
//! takes them and little is held at once.

use rayon::prelude::*;
use std::io::Write;

/// Writes the bytes that `make` appends for each piece `0..count`, in
/// piece order: batches of pieces are made on the rayon pool by a thread
/// of their own while `out` takes the batch before. Returns the bytes
/// written.
///
/// # Errors
/// The first error `out` returns; making stops with it.
pub(crate) fn write_pieces_in_order(
    count: usize,
    make: &(dyn Fn(usize, &mut Vec<u8>) + Sync),
    out: &mut dyn Write,
) -> std::io::Result<u64> {
    // A few pieces per thread at a time: the cores stay busy and at most
    // two batches are held (one being written, one made or waiting).
    let batch = 2 * rayon::current_num_threads();
    let (send, made) = std::sync::mpsc::sync_channel::<Vec<Vec<u8>>>(1);
    std::thread::scope(|scope| {
        scope.spawn(move || {
            for start in (0..count).step_by(batch) {
                let pieces: Vec<Vec<u8>> = (start..(start + batch).min(count))
                    .into_par_iter()
                    .map(|piece| {
                        let mut bytes = Vec::new();
                        make(piece, &mut bytes);
                        bytes
                    })
                    .collect();
                if send.send(pieces).is_err() {
                    // The writer stopped on an error.
                    return;
                }
            }
        });
        let mut written = 0u64;
        for pieces in made {
            for bytes in pieces {
                out.write_all(&bytes)?;
                written += bytes.len() as u64;
            }
        }
        Ok(written)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_are_written_in_order_whatever_order_they_are_made_in() {
        let make = |piece: usize, out: &mut Vec<u8>| {
            // Later pieces are quicker to make, so they finish first.
            std::thread::sleep(std::time::Duration::from_micros(((50 - piece) * 20) as u64));
            out.extend_from_slice(&(piece as u32).to_le_bytes());
        };
        let mut out = Vec::new();
        assert_eq!(write_pieces_in_order(50, &make, &mut out).unwrap(), 200);
        let order: Vec<u32> = out
            .chunks(4)
            .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        assert_eq!(order, (0..50).collect::<Vec<u32>>());
        assert_eq!(write_pieces_in_order(0, &make, &mut Vec::new()).unwrap(), 0);
    }

    #[test]
    fn a_write_error_stops_the_making() {
        struct Full(usize);
        impl Write for Full {
            fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
                if self.0 + b.len() > 100 {
                    return Err(std::io::Error::other("the disk is full"));
                }
                self.0 += b.len();
                Ok(b.len())
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let made = std::sync::atomic::AtomicUsize::new(0);
        let make = |_: usize, out: &mut Vec<u8>| {
            made.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            out.extend_from_slice(&[0; 40]);
        };
        let e = write_pieces_in_order(100_000, &make, &mut Full(0)).unwrap_err();
        assert_eq!(e.to_string(), "the disk is full");
        let made = made.into_inner();
        assert!(
            made < 100,
            "{made} pieces were made after the output failed"
        );
    }
}

use super::*;

fn params(fs_hz: f64) -> CwaWriterParams {
    CwaWriterParams {
        fs_hz,
        acc_range_g: 16.0,
        gyro_range_dps: 2000.0,
        start: "2026-03-02T08:00:00".parse().unwrap(),
        device_id: 42,
        session_id: 7,
        annotation: "_c=ldh test".into(),
    }
}

fn write(fs: f64, n: usize, k0: u64) -> Vec<u8> {
    let mut w = CwaWriter::new(Vec::new(), &params(fs))
        .unwrap()
        .first_index(k0);
    for i in 0..n {
        let x = i as f64;
        w.push([0.001 * x, -1.0, 15.9], [0.5 * x, -300.0, 1999.0])
            .unwrap();
    }
    w.finish().unwrap()
}

#[test]
fn round_trip_in_chunks() {
    let bytes = write(100.0, 1000, 0);
    assert_eq!(bytes.len(), HEADER_BYTES + 25 * BLOCK_BYTES);
    let r = CwaReader::from_reader(&bytes[..], Path::new("x.cwa"), 300).unwrap();
    let info = r.info().clone();
    assert_eq!(info.device, CwaDevice::Ax6);
    assert_eq!((info.device_id, info.session_id), (42, 7));
    assert_eq!(
        (info.fs_hz, info.acc_range_g, info.gyro_range_dps),
        (100.0, 16.0, Some(2000.0))
    );
    assert_eq!(info.start.unwrap().iso(), "2026-03-02T08:00:00");
    assert_eq!(info.annotation, "_c=ldh test");
    let chunks: Vec<CwaChunk> = r.map(|c| c.unwrap()).collect();
    assert_eq!(
        chunks.iter().map(CwaChunk::len).collect::<Vec<_>>(),
        [320, 320, 320, 40]
    );
    let mut i = 0;
    for c in &chunks {
        let g = c.gyro_dps.as_ref().unwrap();
        for j in 0..c.len() {
            let x = i as f64;
            assert!(
                (c.time_s[j] - x / 100.0).abs() < 1e-4,
                "time {} at {i}",
                c.time_s[j]
            );
            assert!((c.acc_g[0][j] - 0.001 * x).abs() <= 0.5 / 2048.0 + 1e-12);
            assert!((c.acc_g[1][j] + 1.0).abs() < 1e-12);
            assert!((g[0][j] - 0.5 * x).abs() <= 0.5 * 2000.0 / 32768.0 + 1e-12);
            assert!((g[2][j] - 1999.0).abs() < 0.04);
            i += 1;
        }
    }
}

#[test]
fn sub_second_starts_are_kept() {
    // Sample 37 first, at 08:00:00.370 at 100 Hz; a 12.5 Hz file too.
    for (fs, k0) in [(100.0, 37), (12.5, 3), (1600.0, 1599)] {
        let bytes = write(fs, 200, k0);
        let r = CwaReader::from_reader(&bytes[..], Path::new("x.cwa"), 1000).unwrap();
        let t0 = r.info().start_unix_s.unwrap() - 1_772_438_400.0;
        assert!((t0 - k0 as f64 / fs).abs() < 5e-5, "{fs} Hz: {t0}");
        let c: Vec<CwaChunk> = r.map(|c| c.unwrap()).collect();
        let last = c.last().unwrap();
        assert!((last.time_s[last.len() - 1] - 199.0 / fs).abs() < 5e-5);
    }
}

#[test]
fn bad_blocks_are_skipped_and_bad_files_refused() {
    let mut bytes = write(50.0, 120, 0);
    bytes[HEADER_BYTES + BLOCK_BYTES + 40] ^= 0xff; // second block's checksum fails
    let mut r = CwaReader::from_reader(&bytes[..], Path::new("x.cwa"), 1000).unwrap();
    assert_eq!(r.next().unwrap().unwrap().len(), 80);
    assert_eq!(r.skipped_blocks(), 1);
    let e = CwaReader::from_reader(&b"time_s,acc_x\n"[..], Path::new("a.csv"), 10).unwrap_err();
    assert!(e.to_string().contains("1024"), "{e}");
    let mut head = write(50.0, 0, 0);
    head[0] = b'X';
    let e = CwaReader::from_reader(&head[..], Path::new("b.cwa"), 10).unwrap_err();
    assert!(e.to_string().contains("not an Axivity"), "{e}");
    let e = CwaWriter::new(
        Vec::new(),
        &CwaWriterParams {
            fs_hz: 120.0,
            ..params(100.0)
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("3200"), "{e}");
}

#[test]
fn packed_ax3_samples_decode() {
    // One AX3 packed block: x = −1 (0x3ff), y = 256 (1 g), z = 3 << 1 with exponent 1.
    let mut b = [0u8; BLOCK_BYTES];
    b[0..2].copy_from_slice(b"AX");
    let t = pack_time(&"2026-03-02T08:00:00".parse().unwrap());
    b[14..18].copy_from_slice(&t.to_le_bytes());
    b[24] = 10; // 100 Hz, ±16 g
    b[25] = 0x30;
    b[28..30].copy_from_slice(&1u16.to_le_bytes());
    let v: u32 = (1 << 30) | (3 << 20) | (128 << 10) | 0x3ff;
    b[30..34].copy_from_slice(&v.to_le_bytes());
    let sum = (0..255).fold(0u16, |s, i| s.wrapping_add(le16(&b, 2 * i)));
    b[510..512].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
    let blk = decode_block(&b, None).unwrap();
    assert_eq!(blk.samples[0][..3], [-2.0 / 256.0, 1.0, 6.0 / 256.0]);
    assert!(!blk.has_gyro);
}

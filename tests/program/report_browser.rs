//! `motionwire report` in a real browser: Debian's `chromium`, headless.
//! The sample's page loads with no console message, its script runs to the
//! end, the DOM after load has one row per device and the marks and bands
//! of docs/report.md#contract in the summary's counts, and a screenshot is
//! not blank.
//!
//! `.ci/run` installs chromium and sets `MOTIONWIRE_BROWSER=required`: then a
//! missing browser fails these tests. Without it (a developer's machine
//! without chromium) they say they were skipped and why, on standard error.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::report_common::{
    check_counts, check_ethercat, parse, repo, run, scratch, summary_records,
};

/// The browser, or `None` (said) when it is not there and not required.
fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("CHROMIUM")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("/usr/bin/chromium"));
    if path.exists() {
        return Some(path);
    }
    let required = std::env::var("MOTIONWIRE_BROWSER").is_ok_and(|v| v == "required");
    assert!(
        !required,
        "MOTIONWIRE_BROWSER=required but there is no browser at {}",
        path.display()
    );
    eprintln!(
        "SKIPPED: no chromium at {} (apt-get install chromium; .ci/run does)",
        path.display()
    );
    None
}

/// Run headless chromium on a page with `args`; its standard output and
/// error.
fn browse(browser: &Path, page: &Path, args: &[&str]) -> (String, String) {
    // A profile per page and use: browsers of tests run at once never
    // share one.
    let name = page.file_stem().unwrap_or_default().to_string_lossy();
    let profile = scratch(&format!("profile-{name}-{}", args.len()));
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn sample_page(dir: &Path) -> PathBuf {
    let out = dir.join("sample.html");
    let r = run(&[
        "report",
        "--profile",
        "3=akd,5=baumer",
        "--heartbeat-ms",
        "300",
        repo("samples/machine.log").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(r.status.success());
    out
}

#[test]
fn the_dom_after_load_agrees_with_the_summary() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("browser-dom");
    let page = sample_page(&dir);
    let (dom, log) = browse(&browser, &page, &["--dump-dom"]);
    let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:#?}");
    let dom = parse(&dom);
    let html = dom.elements.iter().find(|e| e.tag == "html").unwrap();
    assert_eq!(
        html.get("data-script"),
        Some("ready"),
        "the script ran to its end"
    );
    assert!(html.get("class").unwrap_or("").contains("scripted"));
    let records = summary_records(&[
        "--profile",
        "3=akd,5=baumer",
        "--heartbeat-ms",
        "300",
        repo("samples/machine.log").to_str().unwrap(),
    ]);
    check_counts(&dom, &records);
    assert_eq!(dom.summary(), records);
    // The script drew the axis again: ticks are there after load.
    assert!(
        dom.elements
            .iter()
            .filter(|e| e.get("class") == Some("tick"))
            .count()
            > 4
    );
}

/// Decode a PNG (8-bit RGB or RGBA, not interlaced) into its pixels.
fn png_pixels(bytes: &[u8]) -> (u32, u32, usize, Vec<u8>) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let (mut width, mut height, mut channels) = (0, 0, 0);
    let mut idat = Vec::new();
    let mut at = 8;
    while at + 8 <= bytes.len() {
        let len = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let kind = &bytes[at + 4..at + 8];
        let data = &bytes[at + 8..at + 8 + len];
        match kind {
            b"IHDR" => {
                width = u32::from_be_bytes(data[0..4].try_into().unwrap());
                height = u32::from_be_bytes(data[4..8].try_into().unwrap());
                assert_eq!(data[8], 8, "8-bit");
                channels = match data[9] {
                    2 => 3,
                    6 => 4,
                    other => panic!("colour type {other}"),
                };
                assert_eq!(data[12], 0, "not interlaced");
            }
            b"IDAT" => idat.extend_from_slice(data),
            _ => {}
        }
        at += 12 + len;
    }
    let mut raw = Vec::new();
    flate2::read::ZlibDecoder::new(&idat[..])
        .read_to_end(&mut raw)
        .unwrap();
    let stride = width as usize * channels;
    let mut pixels = vec![0u8; stride * height as usize];
    for y in 0..height as usize {
        let filter = raw[y * (stride + 1)];
        let line = &raw[y * (stride + 1) + 1..(y + 1) * (stride + 1)];
        for x in 0..stride {
            let a = if x >= channels {
                pixels[y * stride + x - channels]
            } else {
                0
            };
            let b = if y > 0 {
                pixels[(y - 1) * stride + x]
            } else {
                0
            };
            let c = if x >= channels && y > 0 {
                pixels[(y - 1) * stride + x - channels]
            } else {
                0
            };
            let value = match filter {
                0 => line[x],
                1 => line[x].wrapping_add(a),
                2 => line[x].wrapping_add(b),
                3 => line[x].wrapping_add(((u16::from(a) + u16::from(b)) / 2) as u8),
                4 => {
                    let p = i16::from(a) + i16::from(b) - i16::from(c);
                    let (pa, pb, pc) = (
                        (p - i16::from(a)).abs(),
                        (p - i16::from(b)).abs(),
                        (p - i16::from(c)).abs(),
                    );
                    let pred = if pa <= pb && pa <= pc {
                        a
                    } else if pb <= pc {
                        b
                    } else {
                        c
                    };
                    line[x].wrapping_add(pred)
                }
                other => panic!("filter {other}"),
            };
            pixels[y * stride + x] = value;
        }
    }
    (width, height, channels, pixels)
}

#[test]
fn a_screenshot_is_not_blank() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("browser-shot");
    let page = sample_page(&dir);
    let shot = dir.join("shot.png");
    let (_, log) = browse(
        &browser,
        &page,
        &[
            "--hide-scrollbars",
            "--window-size=1280,1400",
            &format!("--screenshot={}", shot.display()),
        ],
    );
    let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:#?}");
    let (width, height, channels, pixels) = png_pixels(&std::fs::read(&shot).unwrap());
    assert_eq!((width, height), (1280, 1400));
    let total = (width * height) as usize;
    let white = pixels
        .chunks(channels)
        .filter(|p| p[0] > 245 && p[1] > 245 && p[2] > 245)
        .count();
    // The timeline's bands alone cover far more than 3 % of the window.
    let drawn = total - white;
    assert!(
        drawn * 100 > total * 3,
        "only {drawn} of {total} pixels drawn"
    );
    // And in more than a few colours: bands, marks, text.
    let mut colours: Vec<[u8; 3]> = pixels
        .chunks(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 20, "{} colours", colours.len());
}

/// A large log of many devices and many distinct EMCY codes: 100 000
/// frames from 32 nodes — heartbeats, PDOs and 30 000 EMCYs of 4 000
/// codes —, each node lost once (its heartbeat stops for 2 s).
fn large_log(path: &Path) {
    use std::fmt::Write as _;
    let mut log = String::with_capacity(100_000 * 40);
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for i in 0..100_000u64 {
        let us = 1_700_000_000_000_000 + i * 200;
        let (secs, micros) = (us / 1_000_000, us % 1_000_000);
        let node = 1 + (i % 32);
        let r = next();
        // Node n is silent from 2n/3 s for 2 s: one heartbeat timeout each.
        let t = i * 200;
        let silent = t >= node * 600_000 && t < node * 600_000 + 2_000_000;
        let _ = match r % 10 {
            0..=2 => writeln!(
                log,
                "({secs}.{micros:06}) can0 {:03X}#{:04X}{:02X}0000000000",
                0x80 + node,
                ((0x1000 + (r >> 8) % 4000) as u16).swap_bytes(),
                1u8
            ),
            3 if !silent => writeln!(log, "({secs}.{micros:06}) can0 {:03X}#05", 0x700 + node),
            _ => writeln!(
                log,
                "({secs}.{micros:06}) can0 {:03X}#{:016X}",
                0x180 + node,
                r
            ),
        };
    }
    std::fs::write(path, log).unwrap();
}

/// docs/report.md#page: a large log's page shows the verdict and the
/// grouped findings within the first screen (1400 × 1000): the timeline's
/// first band is drawn in the screenshot, below the verdict.
#[test]
fn a_large_logs_verdict_and_findings_fit_the_first_screen() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("browser-large");
    let log = dir.join("large.log");
    large_log(&log);
    let page = dir.join("large.html");
    let r = run(&[
        "report",
        "--heartbeat-ms",
        "300",
        log.to_str().unwrap(),
        "-o",
        page.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let html = std::fs::read_to_string(&page).unwrap();
    let groups = html.matches("<li class=\"group\"").count();
    assert!(groups > 32, "{groups} groups");
    let shot = dir.join("shot.png");
    let (_, log) = browse(
        &browser,
        &page,
        &[
            "--hide-scrollbars",
            "--window-size=1400,1000",
            &format!("--screenshot={}", shot.display()),
        ],
    );
    let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:#?}");
    let (width, height, channels, pixels) = png_pixels(&std::fs::read(&shot).unwrap());
    assert_eq!((width, height), (1400, 1000));
    // The first pixel row with a run of a colour: the verdict's background
    // (#fdf3ee), the timeline's `operational` band (#009E73).
    let first_row = |rgb: [u8; 3]| {
        (0..height as usize).find(|&y| {
            let row = &pixels[y * width as usize * channels..(y + 1) * width as usize * channels];
            row.chunks(channels).filter(|p| p[..3] == rgb).count() >= 20
        })
    };
    let verdict = first_row([0xfd, 0xf3, 0xee]).expect("the verdict is on the first screen");
    let timeline = first_row([0x00, 0x9e, 0x73]).expect("the timeline begins on the first screen");
    assert!(
        verdict < timeline,
        "verdict at {verdict}, timeline at {timeline}"
    );
    assert!(timeline < 1000, "timeline at {timeline}");
}

/// EtherCAT captures' pages in the browser — the synthetic AKD fault, and
/// the drives capture with its servo (its enable bands, servo marks and
/// signal charts) —: the script runs without a console message over slave
/// and stream rows and charts, and the DOM after it ran still agrees with
/// the records (docs/report.md#ethercat).
#[test]
fn an_ethercat_page_after_load_agrees_with_the_summary() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("browser-ecat");
    for (name, capture, options) in [
        (
            "akd",
            "tests/data/ethercat/synthetic_akd_fault.pcapng",
            &[][..],
        ),
        (
            "drives",
            "tests/data/ethercat/drives.pcapng",
            &["--servo", "0x1001"][..],
        ),
    ] {
        let capture = repo(capture);
        let page = dir.join(format!("{name}.html"));
        let mut args = options.to_vec();
        args.push(capture.to_str().unwrap());
        let r = run(&[&["report"][..], &args, &["-o", page.to_str().unwrap()]].concat());
        assert!(r.status.success(), "{name}");
        let (dom, log) = browse(&browser, &page, &["--dump-dom"]);
        let console: Vec<&str> = log.lines().filter(|l| l.contains(":CONSOLE")).collect();
        assert!(console.is_empty(), "{name}: console messages: {console:#?}");
        let dom = parse(&dom);
        let html = dom.elements.iter().find(|e| e.tag == "html").unwrap();
        assert_eq!(html.get("data-script"), Some("ready"), "{name}");
        let records = summary_records(&args);
        check_ethercat(&dom, &records);
        assert_eq!(dom.summary(), records, "{name}");
        if name == "drives" {
            let signals = dom
                .elements
                .iter()
                .filter(|e| e.get("data-kind") == Some("signal"))
                .count();
            // The servo's two, each drive's state, 6064h and 607Ah.
            assert_eq!(signals, 2 + 2 * 3);
            assert!(dom
                .rows
                .iter()
                .any(|r| r.count("servo_enable") > 0 && r.count("servo_fault") > 0));
        }
    }
}

//! Writing the report's SVG marks (docs/report.md#marks): the plain
//! `write!`s of `motionwire::report` against the `svg` crate (0.18, the
//! most used SVG writer on crates.io) in the same run, for the choice
//! issue 23 asks for: a small dependency if one serves, plain writes if
//! they are as clear and faster. Run it with
//! `cargo bench --bench report --features report`; BENCHMARKS.md has the
//! numbers.
//!
//! The input is what the page draws at most (docs/report.md#size): 20 000
//! marks (`report/marks_bare`), or 5 000 marks with their `<title>`
//! (`report/marks_titled`), of every kind of `MarkKind::ALL`, a tenth of
//! them clusters (a `rect` with `data-last-line`), the rest a `use` of the
//! kind's symbol:
//!
//! - `plain`: each element written with `write!` into a `String`, the
//!   attributes in the page's order, as `src/report/html.rs` writes them;
//! - `svg_crate`: each element built as an `svg::node::element::Use` or
//!   `Rectangle` with `.set(name, value)` (and `.add(Title::new(text))`),
//!   then written with its `Display` into the same `String`.
//!
//! Both must write the same elements with the same attributes and titles
//! (checked before timing; the `svg` crate writes attributes sorted by
//! name and its children on lines of their own, the page keeps its order).

use std::fmt::Write as _;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use motionwire::report::MarkKind;
use svg::node::element::{Rectangle, Title, Use};

/// One mark as the page draws it.
struct Mark {
    kind: MarkKind,
    x0: f64,
    width: f64,
    y: f64,
    line: u64,
    last_line: u64,
    count: u64,
    title: String,
}

/// `n` marks spread over the 1 000-pixel plot, deterministic.
fn marks(n: usize) -> Vec<Mark> {
    let mut seed: u64 = 23;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        seed >> 33
    };
    let mut line = 1;
    (0..n)
        .map(|i| {
            let kind = MarkKind::ALL[i % MarkKind::ALL.len()];
            line += 1 + next() % 200;
            let cluster = i % 10 == 0;
            let count = if cluster { 2 + next() % 5_000 } else { 1 };
            let x0 = 170.0 + (next() % 1_000_000) as f64 / 1_000.0;
            Mark {
                kind,
                x0,
                width: if cluster {
                    2.0 + (next() % 8_000) as f64 / 1_000.0
                } else {
                    0.0
                },
                y: if i % 3 == 0 { 7.0 } else { 19.0 },
                line,
                last_line: line + count * 3,
                count,
                title: format!(
                    "{} <0x{:04X}> (line {line}, +{}.{:06} s)",
                    kind.words(),
                    next() % 0x10000,
                    next() % 100,
                    next() % 1_000_000
                ),
            }
        })
        .collect()
}

/// The page's escaping of text and attribute values.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// The marks as `src/report/html.rs` writes them.
fn plain(p: &mut String, marks: &[Mark], titles: bool) {
    for m in marks {
        let name = m.kind.name();
        let element = if m.count > 1 {
            let _ = write!(
                p,
                "<rect x=\"{:.3}\" y=\"{}\" width=\"{:.3}\" height=\"12\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"{}\" data-last-line=\"{}\"",
                m.x0, m.y - 6.0, m.width, m.line, m.count, m.last_line
            );
            "rect"
        } else {
            let _ = write!(
                p,
                "<use href=\"#s-{name}\" x=\"{:.3}\" y=\"{}\" data-kind=\"{name}\" data-line=\"{}\" data-count=\"1\"",
                m.x0, m.y, m.line
            );
            "use"
        };
        if titles {
            let _ = writeln!(p, "><title>{}</title></{element}>", esc(&m.title));
        } else {
            p.push_str("/>\n");
        }
    }
}

/// The same marks built and written by the `svg` crate.
fn svg_crate(p: &mut String, marks: &[Mark], titles: bool) {
    for m in marks {
        let name = m.kind.name();
        if m.count > 1 {
            let mut e = Rectangle::new()
                .set("x", format!("{:.3}", m.x0))
                .set("y", m.y - 6.0)
                .set("width", format!("{:.3}", m.width))
                .set("height", 12)
                .set("data-kind", name)
                .set("data-line", m.line.to_string())
                .set("data-count", m.count.to_string())
                .set("data-last-line", m.last_line.to_string());
            if titles {
                e = e.add(Title::new(m.title.as_str()));
            }
            let _ = writeln!(p, "{e}");
        } else {
            let mut e = Use::new()
                .set("href", format!("#s-{name}"))
                .set("x", format!("{:.3}", m.x0))
                .set("y", m.y)
                .set("data-kind", name)
                .set("data-line", m.line.to_string())
                .set("data-count", 1);
            if titles {
                e = e.add(Title::new(m.title.as_str()));
            }
            let _ = writeln!(p, "{e}");
        }
    }
}

/// An element as a browser reads it: its name, its attributes sorted by
/// name, its title.
type Element = (String, Vec<(String, String)>, String);

/// Each element of `markup`, whatever the attributes' order and the white
/// space between elements.
fn elements(markup: &str) -> Vec<Element> {
    let mut out = Vec::new();
    let mut rest = markup;
    while let Some(at) = rest.find('<') {
        rest = &rest[at + 1..];
        if rest.starts_with('/') || rest.starts_with("title>") {
            let end = rest.find('>').expect("a tag ends");
            if let Some(text) = rest.strip_prefix("title>") {
                let close = text.find("</title>").expect("a title ends");
                let last: &mut Element = out.last_mut().expect("a title is inside an element");
                last.2 = text[..close].replace("&#39;", "'").replace("&apos;", "'");
                rest = &text[close..];
            } else {
                rest = &rest[end..];
            }
            continue;
        }
        let end = rest.find('>').expect("a tag ends");
        let tag = rest[..end].trim_end_matches('/');
        let (name, attrs) = tag.split_once(' ').expect("an element has attributes");
        let mut list: Vec<(String, String)> = attrs
            .split("\" ")
            .map(|a| {
                let (k, v) = a.split_once("=\"").expect("name=\"value\"");
                (k.to_owned(), v.trim_end_matches('"').to_owned())
            })
            .collect();
        list.sort();
        out.push((name.to_owned(), list, String::new()));
        rest = &rest[end..];
    }
    out
}

fn report(c: &mut Criterion) {
    let mut group = c.benchmark_group("report");
    for (id, n, titles) in [("marks_bare", 20_000, false), ("marks_titled", 5_000, true)] {
        let marks = marks(n);
        let (mut a, mut b) = (String::new(), String::new());
        plain(&mut a, &marks, titles);
        svg_crate(&mut b, &marks, titles);
        let (ea, eb) = (elements(&a), elements(&b));
        assert_eq!(ea.len(), n, "{id}: every mark written");
        assert_eq!(ea, eb, "{id}: both write the same elements");
        assert_eq!(
            ea.iter().filter(|e| !e.2.is_empty()).count(),
            if titles { n } else { 0 }
        );
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(format!("{id}/plain"), |bench| {
            let mut p = String::with_capacity(a.len());
            bench.iter(|| {
                p.clear();
                plain(&mut p, black_box(&marks), titles);
                p.len()
            })
        });
        group.bench_function(format!("{id}/svg_crate"), |bench| {
            let mut p = String::with_capacity(b.len());
            bench.iter(|| {
                p.clear();
                svg_crate(&mut p, black_box(&marks), titles);
                p.len()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, report);
criterion_main!(benches);

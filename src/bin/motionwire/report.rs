//! `motionwire report`: the logs read as `decode --summary` reads them, the
//! page written by the library's [`Report`](motionwire::report::Report)
//! (docs/report.md).

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use crate::args::ReportArgs;
use crate::decode;
use crate::failure::Failure;

pub fn run(args: &ReportArgs) -> Result<ExitCode, Failure> {
    if !args.only.is_empty() {
        // docs/report.md#command: the page's states come from every kind.
        return Err(Failure::Usage(
            "report takes no --only: the page reads every kind of frame to draw its states \
             (PDOs are mapped by SDO, NMT states come from heartbeats); narrow it with --node, \
             --id, --iface, --from or --to"
                .to_owned(),
        ));
    }
    let to_stdout = args.output.as_os_str() == "-";
    // A folder that is not there is said before the logs are read.
    if !to_stdout {
        if let Some(parent) = args.output.parent().filter(|p| !p.as_os_str().is_empty()) {
            if !parent.is_dir() {
                return Err(Failure::Usage(format!(
                    "-o {}: the folder {} does not exist",
                    args.output.display(),
                    parent.display()
                )));
            }
        }
    }
    let (code, mut report) = decode::run_page(&args.as_summary())?;
    report.set_command(command_line());
    if to_stdout {
        let mut out = BufWriter::with_capacity(1 << 16, io::stdout().lock());
        report.write_html(&mut out)?;
        out.flush()?;
        return Ok(code);
    }
    let file = File::create(&args.output).map_err(|source| Failure::File {
        path: args.output.clone(),
        source,
    })?;
    let mut out = BufWriter::with_capacity(1 << 16, file);
    report
        .write_html(&mut out)
        .and_then(|()| out.flush())
        .map_err(|source| Failure::File {
            path: args.output.clone(),
            source,
        })?;
    Ok(code)
}

/// The command as it was given, for the page's header.
fn command_line() -> String {
    let mut words = vec!["motionwire".to_owned()];
    words.extend(std::env::args().skip(1));
    words.join(" ")
}

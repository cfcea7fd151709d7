//! `billiard-contact work-precision`: the study's CSV, figure, cost tables and summary, or
//! only the figure and tables redrawn from an existing CSV.

use crate::apps::plot::work_precision as figure;
use crate::apps::work_precision::{self, StudyForce, StudyOptions, StudyRow};
use crate::base::error::Error;
use crate::cli::choice::{whole, ProfileChoice, Trimmed};
use crate::cli::common::{load_two_ball_scene, progress_bar};
use crate::outputs::atomic_file::AtomicFile;
use clap::Args;
use std::path::{Path, PathBuf};

/// The options of `work-precision`.
#[derive(Args)]
pub(super) struct StudyArgs {
    /// Scene file (TOML); the built-in default scene when omitted. Its balls, friction,
    /// impulse and duration are used with every profile (a law scene's realised ones).
    scene: Option<PathBuf>,
    /// Directory for work_precision.csv, .svg, .png and .md (created if missing); the rows a
    /// peer's script appended to an existing work_precision.csv there are kept.
    #[arg(long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    /// Profiles and contact laws (comma-separated): half-sine, hertz, sine-power, rectangle,
    /// tabulated; hertz-law (elastic), hunt-crossley, kuwabara-kono (docs/contact-law.md).
    /// Default: the five profiles, or a law scene's own law.
    #[arg(long, value_delimiter = ',', value_name = "P,...", value_parser = Trimmed::<ProfileChoice>::new())]
    profiles: Option<Vec<ProfileChoice>>,
    /// Timed samples per setting (the median is reported).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 9,
        allow_hyphen_values = true,
        value_parser = whole::<usize>
    )]
    repeats: usize,
    /// Leave out the companion scene in which sliding stops during contact.
    #[arg(long)]
    no_sticking: bool,
    /// Only redraw the figure and the cost tables from DIR/work_precision.csv (e.g. after
    /// benches/peers/scipy_contact.py appended scipy's rows).
    #[arg(long)]
    replot: bool,
}

/// Runs the study (or only redraws its figure) and prints its summary.
pub(super) fn work_precision(args: &StudyArgs) -> Result<(), Error> {
    let csv_path = args.out.join("work_precision.csv");
    let svg = args.out.join("work_precision.svg");
    let png = args.out.join("work_precision.png");
    let md = args.out.join("work_precision.md");
    if args.replot {
        let rows = read_rows(&csv_path)?;
        figure::write(&rows, &svg, &png)?;
        write_tables(&md, &rows)?;
        print!("{}", work_precision::summary(&rows));
        println!(
            "\nwrote {}, {} and {}",
            svg.display(),
            png.display(),
            md.display()
        );
        return Ok(());
    }
    // The rows a peer's script appended to the CSV this run replaces are read first (a
    // malformed file fails before the study runs) and kept.
    let existing = if csv_path.exists() {
        read_rows(&csv_path)?
    } else {
        Vec::new()
    };
    let scene = load_two_ball_scene(args.scene.as_deref(), "work-precision")?;
    let mut options = StudyOptions {
        profiles: match &args.profiles {
            Some(list) => list.iter().map(|p| p.0).collect(),
            None => StudyForce::defaults_for(&scene),
        },
        ..StudyOptions::default()
    };
    if args.repeats == 0 {
        return Err(Error::invalid("--repeats", 0, "at least 1"));
    }
    options.repeats = args.repeats;
    options.sticking_scene = !args.no_sticking;
    std::fs::create_dir_all(&args.out).map_err(|e| Error::io(&args.out, e))?;
    let start = std::time::Instant::now();
    let mut bar: Option<indicatif::ProgressBar> = None;
    let rows = work_precision::run_study(scene, &options, |done, total, row| {
        let b = bar.get_or_insert_with(|| {
            progress_bar(total as u64, "{elapsed:>4} [{bar:40}] {pos}/{len} {msg}")
        });
        b.set_position(done as u64);
        b.set_message(format!("{} {}", row.profile, row.method));
    })?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let own = rows.len();
    let (rows, dropped) = crate::apps::work_precision::csv::with_peers_of(rows, existing);
    write_rows(&csv_path, &rows)?;
    figure::write(&rows, &svg, &png)?;
    write_tables(&md, &rows)?;
    print!("{}", work_precision::summary(&rows));
    for r in rows.iter().filter(|r| !r.note.is_empty()) {
        eprintln!(
            "warning: {} {} {:?} failed: {}",
            r.profile, r.method, r.rtol, r.note
        );
    }
    if rows.len() > own || dropped > 0 {
        println!(
            "\nkept {} peer rows of {} (their scenes and profiles); dropped {dropped} of \
             scenes or profiles not run now",
            rows.len() - own,
            csv_path.display()
        );
    }
    println!(
        "\nwrote {}, {}, {} and {} in {:.1} s",
        csv_path.display(),
        svg.display(),
        png.display(),
        md.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The rows of the study CSV at `path`.
fn read_rows(path: &Path) -> Result<Vec<StudyRow>, Error> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    work_precision::read_csv(std::io::BufReader::new(file), path)
}

/// The cost tables in Markdown, written whole or not at all.
fn write_tables(path: &Path, rows: &[StudyRow]) -> Result<(), Error> {
    use std::io::Write;
    let mut file = AtomicFile::create(path)?;
    file.write_all(work_precision::markdown(rows).as_bytes())
        .map_err(|e| Error::io(path, e))?;
    file.commit()
}

/// The study's CSV, written whole or not at all.
fn write_rows(path: &Path, rows: &[StudyRow]) -> Result<(), Error> {
    let mut file = AtomicFile::create(path)?;
    work_precision::write_csv(&mut file, rows)?;
    file.commit()
}

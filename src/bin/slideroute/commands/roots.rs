//! `slideroute roots`: every root of the pose system at one displacement, classified, the
//! physical one selected; or, with `--grid`, the same for every pose of a CSV file, on every
//! core, a few dozen poses at a time solved together, written in the file's order.

use super::{displacement, load, print_json};
use crate::cli::RootsArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, out, output_error};
use rayon::prelude::*;
use slideroute::output::{GridPose, GridPoses, GridRows, RootsReport};
use slideroute::poses::{BatchSolver, solve_all_batch};
use slideroute::{Displacement, Mode, Scene};
use std::path::Path;

/// Runs `slideroute roots`.
pub fn roots(args: &RootsArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let mode = args
        .mode
        .or(scene.settings().map(|s| s.mode))
        .unwrap_or(Mode::Exact);
    if let (Some(grid), Some(out)) = (&args.grid, &args.out) {
        return roots_grid(&scene, mode, grid, out);
    }
    let r = report(&scene, mode, displacement(&args.pose)?).map_err(bad_input)?;
    if args.json {
        print_json(&r)
    } else {
        out!("{r}");
        Ok(())
    }
}

/// Every root at `d`, as the report prints it.
fn report(scene: &Scene, mode: Mode, d: Displacement) -> Result<RootsReport, String> {
    slideroute::poses::solve_all(scene.site(), d, mode)
        .map(|all| RootsReport::new(scene, &all))
        .map_err(|e| e.to_string())
}

/// The poses solved at a time: read, solved on every core, written, then the next; memory is
/// bounded by this whatever the file's length.
const CHUNK: usize = 4096;

/// The report of every pose of the file `grid`, written to `out`: whole, under a temporary name
/// beside it renamed into place when done, so that an earlier file there stays whole until then
/// (a device or a pipe, such as /dev/null, is written to directly). Ctrl-C stops it at the next
/// chunk, leaving no file.
fn roots_grid(scene: &Scene, mode: Mode, grid: &Path, out: &Path) -> Result<(), CliError> {
    let name = grid.display().to_string();
    // Only a regular file, of any length (a line is bounded instead).
    let poses = GridPoses::open(grid).map_err(output_error)?;
    let out_name = out.display().to_string();
    if same_file(grid, out) {
        return Err(bad_input(format!(
            "{out_name}: is the grid itself (--grid {name}): its poses would be replaced by \
             their roots; give --out another file"
        )));
    }
    let target = Target::new(out).map_err(|e| failed(format!("{out_name}: {e}")))?;
    let result = solve_grid(scene, mode, poses, target.writer(), CHUNK, &out_name);
    match result {
        Ok(n) => {
            target
                .finish()
                .map_err(|e| failed(format!("{out_name}: {e}")))?;
            eprintln!("slideroute: {n} poses written to {out_name}");
            Ok(())
        }
        Err(e) => {
            target.abandon();
            Err(e)
        }
    }
}

/// Whether `a` and `b` name one file (the same device and inode, through links or not); a
/// path that is not there names no file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(a), Ok(b)) => {
            use std::os::unix::fs::MetadataExt;
            (a.dev(), a.ino()) == (b.dev(), b.ino())
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => std::fs::canonicalize(a).ok() == std::fs::canonicalize(b).ok(),
        _ => false,
    }
}

/// Every pose of `poses`, `chunk` at a time (on every core, in order), written to `out`
/// (`out_name` in a failure's message); the number written.
fn solve_grid<R: std::io::Read, W: std::io::Write>(
    scene: &Scene,
    mode: Mode,
    mut poses: GridPoses<R>,
    out: W,
    chunk: usize,
    out_name: &str,
) -> Result<usize, CliError> {
    let write_err = |e: csv::Error| failed(format!("{out_name}: cannot write: {e}"));
    let mut w = GridRows::new(out).map_err(write_err)?;
    let mut batch = Vec::with_capacity(chunk);
    let mut n = 0;
    loop {
        batch.clear();
        for pose in poses.by_ref().take(chunk) {
            batch.push(pose.map_err(output_error)?);
        }
        if batch.is_empty() {
            break;
        }
        if interrupted() {
            return Err(failed(format!(
                "interrupted after {n} poses; nothing written"
            )));
        }
        let reports = reports(scene, mode, &batch).map_err(bad_input)?;
        w.rows(&batch, &reports).map_err(write_err)?;
        n += batch.len();
    }
    w.finish().map_err(write_err)?;
    Ok(n)
}

/// The poses solved in order on one core, each continued from the one before (`BatchSolver`):
/// the roots of one at a time to their accuracy. A fixed number, so that the output does not
/// depend on the number of threads.
const SUBBATCH: usize = 64;

/// The report of every pose of `poses`, in order: [`SUBBATCH`] poses at a time on every core.
fn reports(scene: &Scene, mode: Mode, poses: &[GridPose]) -> Result<Vec<RootsReport>, String> {
    let parts: Vec<Vec<Result<RootsReport, String>>> = poses
        .par_chunks(SUBBATCH)
        .map_init(BatchSolver::new, |solver, part| {
            let ds: Vec<Displacement> = part.iter().map(GridPose::displacement).collect();
            solve_all_batch(scene.site(), &ds, mode, solver)
                .into_iter()
                .map(|all| {
                    all.map(|all| RootsReport::new(scene, &all))
                        .map_err(|e| e.to_string())
                })
                .collect()
        })
        .collect();
    parts.into_iter().flatten().collect()
}

/// Where the rows go: a temporary file beside `out` (made new, never through a link), renamed
/// over it at the end; or `out` itself where it is a device or a pipe.
struct Target {
    out: std::path::PathBuf,
    tmp: Option<std::path::PathBuf>,
    file: std::fs::File,
}

impl Target {
    fn new(out: &Path) -> Result<Target, String> {
        let special = std::fs::metadata(out).is_ok_and(|m| !m.is_file() && !m.is_dir());
        if special {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(out)
                .map_err(|e| format!("cannot write: {e}"))?;
            return Ok(Target {
                out: out.to_path_buf(),
                tmp: None,
                file,
            });
        }
        let file_name = out
            .file_name()
            .ok_or("not a file name")?
            .to_string_lossy()
            .into_owned();
        let tmp = out.with_file_name(format!(".{file_name}.{}.tmp", std::process::id()));
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| format!("cannot write {}: {e}", tmp.display()))?;
        Ok(Target {
            out: out.to_path_buf(),
            tmp: Some(tmp),
            file,
        })
    }

    fn writer(&self) -> std::io::BufWriter<&std::fs::File> {
        std::io::BufWriter::with_capacity(1 << 16, &self.file)
    }

    /// The rows in place: the temporary synced and renamed over `out`.
    fn finish(self) -> Result<(), String> {
        let Some(tmp) = &self.tmp else {
            return Ok(());
        };
        let done = self
            .file
            .sync_all()
            .and_then(|()| std::fs::rename(tmp, &self.out));
        if let Err(e) = done {
            let _ = std::fs::remove_file(tmp);
            return Err(format!("cannot write: {e}"));
        }
        Ok(())
    }

    /// No file: the temporary removed, an earlier `out` left as it was.
    fn abandon(self) {
        if let Some(tmp) = &self.tmp {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(text: &str, chunk: usize) -> Result<String, CliError> {
        let scene = Scene::default_scene();
        let poses = GridPoses::from_reader(text.as_bytes(), "g.csv").map_err(output_error)?;
        let mut out = Vec::new();
        solve_grid(&scene, Mode::Exact, poses, &mut out, chunk, "out.csv")?;
        Ok(String::from_utf8(out).unwrap())
    }

    /// The same rows, every field equal but the four numbers of a selected pose, which agree to
    /// 10⁻⁹ relative (a pose continued from another, or solved afresh, has its roots to their
    /// accuracy, not to the last bit: `roots/batch.rs`).
    fn assert_rows_agree(got: &str, want: &str, what: &str) {
        assert_eq!(got.lines().count(), want.lines().count(), "{what}");
        for (g, w) in got.lines().zip(want.lines()) {
            let (g, w): (Vec<&str>, Vec<&str>) = (g.split(',').collect(), w.split(',').collect());
            assert_eq!(g.len(), w.len(), "{what}: {g:?} against {w:?}");
            for (k, (a, b)) in g.iter().zip(&w).enumerate() {
                match (a.parse::<f64>(), b.parse::<f64>()) {
                    (Ok(a), Ok(b)) if (4..8).contains(&k) => assert!(
                        (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                        "{what}: column {k}: {a} against {b}"
                    ),
                    _ => assert_eq!(a, b, "{what}: column {k}"),
                }
            }
        }
    }

    #[test]
    fn a_grid_solved_in_chunks_gives_the_rows_of_one_pose_at_a_time() {
        let mut text = String::from("x_m,z_m,theta_deg\n");
        for k in 0..11 {
            text.push_str(&format!(
                "{},{},{}\n",
                0.1 * k as f64,
                0.02 * k as f64,
                k as f64 / 4.0
            ));
        }
        let whole = rows(&text, 1000).unwrap();
        for chunk in [1, 3, 4, 11] {
            assert_rows_agree(
                &rows(&text, chunk).unwrap(),
                &whole,
                &format!("chunk {chunk}"),
            );
        }
        assert_eq!(whole.lines().count(), 12);
        // Row k is pose k's report, as `roots` gives it alone.
        let third = report(
            &Scene::default_scene(),
            Mode::Exact,
            Displacement::new(0.2, 0.04, 0.5f64.to_radians()),
        )
        .unwrap();
        let third = serde_json::to_value(&third).unwrap();
        let alpha = third["selected"]["alpha_deg"].as_f64().unwrap();
        let row: f64 = whole
            .lines()
            .nth(3)
            .unwrap()
            .split(',')
            .nth(4)
            .unwrap()
            .parse()
            .unwrap();
        assert!(
            (row - alpha).abs() <= 1e-9 * alpha.abs(),
            "{row} against {alpha}"
        );
    }

    #[test]
    fn a_grid_gives_the_rows_of_its_poses_solved_one_at_a_time() {
        // Random poses, θ = 0 (the double roots of the small-angle system) and poses with no
        // admissible root, over more than one sub-batch.
        let mut text = String::from("x_m,z_m,theta_deg\n");
        let mut s = 7u64;
        let mut uniform = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..300 {
            let theta = if k % 10 == 0 {
                0.0
            } else {
                6.0 * uniform() - 3.0
            };
            let x = if k % 50 == 1 { 1.0 } else { 0.5 * uniform() };
            let theta = if k % 50 == 1 { -30.0 } else { theta };
            text.push_str(&format!("{x},{},{theta}\n", 0.4 * uniform() - 0.2));
        }
        let scene = Scene::default_scene();
        for mode in [Mode::Exact, Mode::SmallAngle] {
            let poses = GridPoses::from_reader(text.as_bytes(), "g.csv").unwrap();
            let mut batched = Vec::new();
            solve_grid(&scene, mode, poses, &mut batched, 256, "out.csv").unwrap();
            let poses: Vec<GridPose> = GridPoses::from_reader(text.as_bytes(), "g.csv")
                .unwrap()
                .map(Result::unwrap)
                .collect();
            let alone: Vec<RootsReport> = poses
                .iter()
                .map(|p| report(&scene, mode, p.displacement()).unwrap())
                .collect();
            let mut w = GridRows::new(Vec::new()).unwrap();
            w.rows(&poses, &alone).unwrap();
            let alone = w.finish().unwrap();
            assert!(String::from_utf8_lossy(&alone).contains("no admissible root"));
            assert_rows_agree(
                &String::from_utf8(batched).unwrap(),
                &String::from_utf8(alone).unwrap(),
                &format!("{mode:?}"),
            );
        }
    }

    #[test]
    fn a_line_longer_than_a_pose_can_be_is_refused_naming_its_line() {
        let long = format!("x_m,z_m,theta_deg\n0.1,0,0\n0.2,0,{}\n", "1".repeat(5000));
        let Err(CliError::BadInput(e)) = rows(&long, 4) else {
            panic!("accepted")
        };
        assert!(
            e.contains("g.csv: line 3") && e.contains("longer than 4096"),
            "{e}"
        );
    }
}

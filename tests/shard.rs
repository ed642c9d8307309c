//! Scaling out: a render cut into shards, each rendered apart into a partial result, merges
//! into bit for bit the result of one run (films, receivers, energy budget); a killed render
//! resumes to the same result; partials of different renders are refused, naming the
//! difference.

use grinlight::commands::{self, MergeJob, Observer, Overrides, RenderJob, RenderOutcome};
use grinlight::settings::{
    Key, CAUSTIC_PHOTONS, HEIGHT, PASSES, PHOTONS, RECEIVER_PHOTONS, SEED, SPP, TARGET_ERROR,
    THREADS, TIME_BUDGET, WIDTH,
};
use grinlight::shard::{Partial, Shard};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// A fresh directory holding copies of the Cornell box and the LED-lit fiber scenes, clear
/// and with scattering particles in its core.
fn workspace(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("grinlight-shard-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy("scenes/cornell_caustic.toml", dir.join("cornell.toml")).unwrap();
    std::fs::copy("scenes/fiber_led.toml", dir.join("fiber.toml")).unwrap();
    std::fs::copy("scenes/diffusing_fiber.toml", dir.join("diffusing.toml")).unwrap();
    dir
}

/// Overrides giving each of `values`.
fn given(values: &[(&'static Key, u64)]) -> Overrides {
    let mut o = Overrides::default();
    for &(key, value) in values {
        o.set(key, value);
    }
    o
}

/// A small Cornell render: 7 passes of photon maps (progressive caustics), so that every
/// shard count up to 7 has passes to do.
fn cornell(dir: &Path) -> RenderJob {
    RenderJob {
        scene: dir.join("cornell.toml"),
        overrides: given(&[
            (&WIDTH, 24),
            (&HEIGHT, 18),
            (&SPP, 1),
            (&PHOTONS, 3_000),
            (&CAUSTIC_PHOTONS, 3_000),
            (&PASSES, 7),
            (&THREADS, 2),
        ]),
        ..RenderJob::default()
    }
}

/// The fiber measured with 30 000 receiver photons.
fn fiber(dir: &Path) -> RenderJob {
    receivers(dir, "fiber.toml")
}

/// The receivers of scene `file` in `dir`, from 30 000 photons.
fn receivers(dir: &Path, file: &str) -> RenderJob {
    RenderJob {
        scene: dir.join(file),
        overrides: given(&[(&RECEIVER_PHOTONS, 30_000), (&THREADS, 2)]),
        ..RenderJob::default()
    }
}

/// Renders `job` whole into `dir/name.exr`, then as N shards merged into `dir/name-N.exr`.
fn whole_and_merged(
    dir: &Path,
    job: &RenderJob,
    name: &str,
    n: u32,
) -> (RenderOutcome, RenderOutcome) {
    let whole = commands::render(
        &RenderJob {
            output: Some(dir.join(format!("{name}.exr"))),
            ..job.clone()
        },
        &(),
    )
    .unwrap();
    let mut partials = Vec::new();
    // Shards in reverse order: the order of the work does not matter.
    for k in (1..=n).rev() {
        let path = dir.join(format!("{name}-{k}-of-{n}.partial"));
        let shard = commands::render(
            &RenderJob {
                output: Some(path.clone()),
                shard: Some(Shard { index: k, count: n }),
                ..job.clone()
            },
            &(),
        )
        .unwrap();
        assert!(!shard.interrupted);
        partials.push(path);
    }
    let merged = commands::merge(
        &MergeJob {
            partials,
            output: Some(dir.join(format!("{name}-{n}.exr"))),
            allow_missing: false,
        },
        &(),
    )
    .unwrap();
    (whole, merged)
}

/// N = 1, 2, 3, 7 shards of the fiber receiver, of the diffusing fiber's and of a Cornell render
/// merge into the single run's result: every film sum, every bin's irradiance and standard
/// error, every energy-budget entry (with the diffusing fiber's scattered part) identical to
/// the bit (`==` on f64 and on the fixed-point sums);
/// the EXR files byte for byte. The progressive caustic is included: its radius schedule is a
/// function of the pass index alone, so a pass is the same pass in any shard.
#[test]
fn shards_merge_into_the_single_run_bit_for_bit() {
    let dir = workspace("merge");
    for n in [1, 2, 3, 7] {
        let (whole, merged) = whole_and_merged(&dir, &cornell(&dir), "cornell", n);
        let (a, b) = (
            &whole.film.as_ref().unwrap().film,
            &merged.film.as_ref().unwrap().film,
        );
        assert_eq!(a, b, "Cornell film, {n} shards");
        assert!(
            a.counts().iter().all(|&c| c == 7),
            "every pixel has 7 passes"
        );
        assert_eq!(
            std::fs::read(dir.join("cornell.exr")).unwrap(),
            std::fs::read(dir.join(format!("cornell-{n}.exr"))).unwrap(),
            "Cornell EXR, {n} shards"
        );
        let (whole, merged) = whole_and_merged(&dir, &fiber(&dir), "fiber", n);
        assert_eq!(whole.measurements, merged.measurements, "fiber, {n} shards");
        assert_eq!(whole.budget, merged.budget, "fiber budget, {n} shards");
        assert!(whole.measurements[0].flux.0 > 0.0);
        assert_eq!(
            std::fs::read(dir.join("fiber.exit.csv")).unwrap(),
            std::fs::read(dir.join(format!("fiber-{n}.exit.csv"))).unwrap()
        );
        let job = receivers(&dir, "diffusing.toml");
        let (whole, merged) = whole_and_merged(&dir, &job, "diffusing", n);
        assert_eq!(
            whole.measurements, merged.measurements,
            "diffusing, {n} shards"
        );
        let budget = whole.budget.as_ref().unwrap();
        assert!(budget.scattered.is_some(), "the core scatters");
        assert_eq!(
            whole.budget, merged.budget,
            "diffusing fiber budget, {n} shards"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

fn grinlight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run grinlight")
}

/// Starts `grinlight render ARGS` in `dir` and SIGKILLs it once `watch` has been saved
/// `saves` times (its modification time changed), at most 120 s on.
fn kill_after_saves(dir: &Path, args: &[&str], watch: &str, saves: usize) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let (mut seen, mut last) = (0, None);
    while seen < saves {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{watch} not saved"
        );
        assert!(child.try_wait().unwrap().is_none(), "ended before the kill");
        let modified = std::fs::metadata(dir.join(watch))
            .and_then(|m| m.modified())
            .ok();
        if modified.is_some() && modified != last {
            seen += 1;
            last = modified;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
}

/// `kill -9` in the middle of a render, then `--resume`: the same result as an
/// uninterrupted render — for a camera render (after two of twelve passes: the EXR byte for
/// byte) and for a receiver shard (after one of two blocks of photons: the partial's books
/// bit for bit).
#[test]
fn a_killed_render_resumes_to_the_same_result() {
    let dir = workspace("resume");
    let camera = [
        "render",
        "cornell.toml",
        "--width",
        "32",
        "--height",
        "24",
        "--spp",
        "1",
        "--photons",
        "20000",
        "--caustic-photons",
        "20000",
        "--passes",
        "12",
        "--checkpoint",
        "1",
        "--threads",
        "1",
    ];
    let with = |extra: &[&'static str]| [&camera[..], extra].concat();
    assert!(grinlight(&dir, &with(&["-o", "whole.exr"]))
        .status
        .success());
    kill_after_saves(&dir, &with(&["-o", "killed.exr"]), "killed.partial", 2);
    let saved = Partial::read(&dir.join("killed.partial")).unwrap();
    assert!(!saved.is_complete(), "killed after the render ended");
    // Starting again without --resume would throw the saved passes away: refused.
    let again = grinlight(&dir, &with(&["-o", "killed.exr"]));
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--resume"));
    let resumed = grinlight(&dir, &with(&["-o", "killed.exr", "--resume"]));
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_eq!(
        std::fs::read(dir.join("whole.exr")).unwrap(),
        std::fs::read(dir.join("killed.exr")).unwrap()
    );
    assert!(
        !dir.join("killed.partial").exists(),
        "a finished render keeps no state"
    );

    // A receiver shard of two blocks of photons, killed after the first.
    let photons = (grinlight::shard::BLOCK + 120_000).to_string();
    let shard = [
        "render",
        "fiber.toml",
        "--shard",
        "1/1",
        "--receiver-photons",
        &photons,
        "--checkpoint",
        "1",
    ];
    let out = |o: &'static str| [&shard[..], &["-o", o]].concat();
    assert!(grinlight(&dir, &out("whole.partial")).status.success());
    kill_after_saves(
        &dir,
        &out("killed-fiber.partial"),
        "killed-fiber.partial",
        1,
    );
    let saved = Partial::read(&dir.join("killed-fiber.partial")).unwrap();
    assert_eq!(saved.photons.len(), grinlight::shard::BLOCK);
    let resume = [&out("killed-fiber.partial")[..], &["--resume"]].concat();
    assert!(grinlight(&dir, &resume).status.success());
    let (a, b) = (
        Partial::read(&dir.join("whole.partial")).unwrap(),
        Partial::read(&dir.join("killed-fiber.partial")).unwrap(),
    );
    assert_eq!(a.books, b.books);
    assert_eq!(a.photons, b.photons);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Merging partials that are not parts of one render is refused with a message
/// naming the difference; so are duplicates, overlaps, missing shards (unless allowed), files
/// that are not partials, and a resume with other options.
#[test]
fn mismatched_partials_are_refused_naming_the_difference() {
    let dir = workspace("refuse");
    let shard = |k: u32, n: u32, seed: u64, out: &str| {
        let mut job = cornell(&dir);
        job.overrides.set(&SEED, seed);
        job.overrides.set(&PASSES, 2);
        job.shard = Some(Shard { index: k, count: n });
        job.output = Some(dir.join(out));
        commands::render(&job, &()).unwrap();
        dir.join(out)
    };
    let a = shard(1, 2, 1, "a.partial");
    let b = shard(2, 2, 1, "b.partial");
    let other_seed = shard(2, 2, 9, "seed.partial");
    let of_three = shard(2, 3, 1, "three.partial");
    let mut fib = fiber(&dir);
    fib.shard = Some(Shard { index: 2, count: 2 });
    fib.output = Some(dir.join("fiber.partial"));
    commands::render(&fib, &()).unwrap();
    std::fs::write(dir.join("notes.partial"), "my notes\n").unwrap();
    let merge = |parts: &[&Path], allow_missing: bool| {
        commands::merge(
            &MergeJob {
                partials: parts.iter().map(|p| p.to_path_buf()).collect(),
                output: Some(dir.join("m.exr")),
                allow_missing,
            },
            &(),
        )
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default()
    };
    let cases: &[(&[&Path], &str)] = &[
        (&[&a, &other_seed], "seed: 1 against 9"),
        (&[&a, &of_three], "shard count"),
        (&[&a, &dir.join("fiber.partial")], "scene"),
        (&[&a, &a], "both shard 1/2"),
        (&[&a], "lack passes 1..2 of 2"),
        (&[&a, &dir.join("notes.partial")], "not a grinlight partial"),
        (&[&a, &dir.join("gone.partial")], "gone.partial"),
    ];
    for (parts, want) in cases {
        let message = merge(parts, false);
        assert!(
            message.contains(want),
            "{parts:?}: {message:?} lacks {want:?}"
        );
    }
    assert_eq!(merge(&[&b, &a], false), "");
    // A whole render whose saved state would be `a.partial` (it renders to `a.exr`) leaves
    // that shard's result alone; the same shard run again replaces its own finished partial.
    let before = std::fs::read(&a).unwrap();
    let mut whole = cornell(&dir);
    whole.overrides.set(&PASSES, 2);
    whole.overrides.set(&SEED, 1);
    whole.output = Some(dir.join("a.exr"));
    let e = commands::render(&whole, &()).err().unwrap().to_string();
    assert!(
        e.contains("holds a shard's result (made by `render --shard`"),
        "{e}"
    );
    assert_eq!(std::fs::read(&a).unwrap(), before);
    assert_eq!(shard(1, 2, 1, "a.partial"), a);
    // With --allow-missing, one shard of two gives the film of its pass, marked partial.
    let lone = commands::merge(
        &MergeJob {
            partials: vec![a.clone()],
            output: Some(dir.join("lone.exr")),
            allow_missing: true,
        },
        &(),
    )
    .unwrap();
    assert!(lone.incomplete && !lone.interrupted);
    // From the command line it exits 0 (done; 130 is for an interrupt) and says PARTIAL.
    let out = grinlight(
        &dir,
        &[
            "merge",
            a.to_str().unwrap(),
            "--allow-missing",
            "-o",
            "lone-cli.exr",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("PARTIAL: passes 1..2 missing"));
    // A scene edited after its shards were rendered is refused at the merge.
    let text = std::fs::read_to_string(dir.join("cornell.toml")).unwrap();
    std::fs::write(
        dir.join("cornell.toml"),
        text.replace("spp = 16", "spp = 15"),
    )
    .unwrap();
    assert!(merge(&[&a, &b], false).contains("changed since"));
    std::fs::write(dir.join("cornell.toml"), text).unwrap();
    // Resuming with other options names the difference.
    let mut job = cornell(&dir);
    job.overrides.set(&PASSES, 2);
    job.overrides.set(&SEED, 3);
    job.shard = Some(Shard { index: 1, count: 2 });
    job.output = Some(a.clone());
    job.resume = true;
    let e = commands::render(&job, &()).err().unwrap().to_string();
    assert!(e.contains("seed: 3 against 1"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Slurm recipe's job scripts (`cluster/slurm/`), run as plain local processes with the
/// environment a job array gives its tasks: three shard tasks (the second one twice, as a
/// requeued task would be: it resumes its own finished partial) and the merge task give the
/// single run's receiver files byte for byte. (`cluster/slurm/local-test.sh` runs them under a
/// real single-node Slurm; it needs root, so it is not part of CI.)
#[test]
fn the_slurm_job_scripts_run_as_local_processes() {
    let dir = workspace("slurm");
    let repo = std::env::current_dir().unwrap();
    let script = |name: &str| repo.join("cluster/slurm").join(name);
    let run = |args: &[&str], task: Option<u32>| {
        let mut c = Command::new("bash");
        c.args(args)
            .current_dir(&dir)
            .env("GRINLIGHT", env!("CARGO_BIN_EXE_grinlight"));
        if let Some(k) = task {
            c.env("SLURM_ARRAY_TASK_ID", k.to_string())
                .env("SLURM_ARRAY_TASK_COUNT", "3");
        }
        let out = c.output().unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    std::fs::create_dir_all(dir.join("out")).unwrap();
    let render = script("render.sbatch");
    let render = render.to_str().unwrap();
    for k in [1, 2, 2, 3] {
        run(
            &[render, "fiber.toml", "out", "--receiver-photons", "20000"],
            Some(k),
        );
    }
    run(
        &[script("merge.sbatch").to_str().unwrap(), "out", "3"],
        None,
    );
    assert!(grinlight(
        &dir,
        &[
            "render",
            "fiber.toml",
            "--receiver-photons",
            "20000",
            "-o",
            "one.exr"
        ]
    )
    .status
    .success());
    assert_eq!(
        std::fs::read(dir.join("one.exit.csv")).unwrap(),
        std::fs::read(dir.join("out/result.exit.csv")).unwrap()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A render ended by its time budget is whole with the passes that fitted: not partial, no
/// saved state left behind, every pixel with the same passes.
#[test]
fn a_time_budget_ends_a_whole_render() {
    let dir = workspace("budget");
    let mut job = cornell(&dir);
    job.overrides.unset(&PASSES);
    job.overrides.set(&TIME_BUDGET, 0.3);
    job.output = Some(dir.join("b.exr"));
    let outcome = commands::render(&job, &()).unwrap();
    assert!(!outcome.interrupted);
    let rendered = outcome.film.unwrap();
    assert!(rendered.report.passes >= 1);
    assert_eq!(rendered.passes, rendered.report.passes);
    assert!(rendered
        .film
        .counts()
        .iter()
        .all(|&c| c == rendered.passes as u64));
    assert!(!dir.join("b.partial").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A finished shard's result is never replaced nor removed by a whole render whose saved
/// state would be at its path: not when the render finishes (it would remove its state), not
/// when it checkpoints and is killed (it would save a few passes over the finished shard).
/// The render is refused before any work, the file is untouched, and it still merges.
#[test]
fn a_whole_render_leaves_a_finished_shard_result_alone() {
    let dir = workspace("keep-shard");
    let x = dir.join("x.partial");
    let mut job = cornell(&dir);
    job.overrides.set(&PASSES, 3);
    job.shard = Some(Shard::WHOLE);
    job.output = Some(x.clone());
    commands::render(&job, &()).unwrap();
    let before = std::fs::read(&x).unwrap();
    for checkpoint in [0, 1] {
        let whole = RenderJob {
            shard: None,
            output: Some(dir.join("x.exr")),
            checkpoint,
            ..job.clone()
        };
        let e = commands::render(&whole, &()).err().unwrap().to_string();
        assert!(e.contains("holds a shard's result"), "{e}");
        assert_eq!(std::fs::read(&x).unwrap(), before, "x.partial untouched");
        assert!(!dir.join("x.exr").exists(), "no work was done");
    }
    let merged = commands::merge(
        &MergeJob {
            partials: vec![x.clone()],
            output: Some(dir.join("m.exr")),
            allow_missing: false,
        },
        &(),
    )
    .unwrap();
    assert!(!merged.incomplete);
    // The shard run again over its own finished result finishes from it: the same bytes.
    commands::render(&job, &()).unwrap();
    assert_eq!(std::fs::read(&x).unwrap(), before);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Stops a render after its first finished pass (an interrupt, as Ctrl-C gives).
struct StopAfterFirstPass(std::sync::atomic::AtomicBool);

impl Observer for StopAfterFirstPass {
    fn pass_done(
        &self,
        _: u32,
        _: &dyn Fn() -> grinlight::film::Film,
    ) -> grinlight::error::Result<()> {
        self.0.store(true, std::sync::atomic::Ordering::SeqCst);
        Ok(())
    }
    fn stop_requested(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::SeqCst)
    }
}

/// Evidence: a byte flipped at every 1 % of a partial file — a merged shard's and an
/// interrupted render's saved state — is refused before anything is merged or resumed,
/// naming the file, and never panics; the merge writes nothing, the resume neither.
#[test]
fn damaged_partials_are_refused_before_any_merge_or_resume() {
    let dir = workspace("flip");
    let mut job = cornell(&dir);
    job.overrides.set(&PASSES, 3);
    job.overrides.set(&WIDTH, 16);
    job.overrides.set(&HEIGHT, 12);
    let shards: Vec<PathBuf> = (1..=3)
        .map(|k| {
            let path = dir.join(format!("s{k}.partial"));
            commands::render(
                &RenderJob {
                    shard: Some(Shard { index: k, count: 3 }),
                    output: Some(path.clone()),
                    ..job.clone()
                },
                &(),
            )
            .unwrap();
            path
        })
        .collect();
    // An interrupted whole render: its state k.partial holds one pass of three.
    let whole = RenderJob {
        output: Some(dir.join("k.exr")),
        ..job.clone()
    };
    let stopped = commands::render(&whole, &StopAfterFirstPass(Default::default())).unwrap();
    assert!(stopped.interrupted);
    let state = dir.join("k.partial");
    let flip_each_percent = |path: &Path, attempt: &dyn Fn() -> Option<String>| {
        let good = std::fs::read(path).unwrap();
        for percent in 0..100 {
            let at = good.len() * percent / 100;
            let mut bad = good.clone();
            bad[at] ^= 0x5a;
            std::fs::write(path, &bad).unwrap();
            let e = attempt().unwrap_or_else(|| panic!("{path:?}: byte {at} flipped, accepted"));
            assert!(
                e.contains(&*path.to_string_lossy()) && !e.contains("panicked"),
                "byte {at}: {e}"
            );
        }
        std::fs::write(path, &good).unwrap();
    };
    let out = dir.join("m.exr");
    flip_each_percent(&shards[1], &|| {
        let r = commands::merge(
            &MergeJob {
                partials: shards.clone(),
                output: Some(out.clone()),
                allow_missing: false,
            },
            &(),
        );
        assert!(!out.exists(), "a damaged merge wrote its image");
        r.err().map(|e| e.to_string())
    });
    flip_each_percent(&state, &|| {
        let r = commands::render(
            &RenderJob {
                resume: true,
                ..whole.clone()
            },
            &(),
        );
        r.err().map(|e| e.to_string())
    });
    // Truncated or grown by a byte: refused by its lengths, before its payload is read.
    let good = std::fs::read(&shards[1]).unwrap();
    for bad in [&good[..good.len() - 1], &[&good[..], &[0]].concat()[..]] {
        std::fs::write(&shards[1], bad).unwrap();
        let e = Partial::read(&shards[1]).err().unwrap().to_string();
        assert!(e.contains("bytes where its lengths say"), "{e}");
    }
    // Undamaged, both work.
    std::fs::write(&shards[1], &good).unwrap();
    commands::render(
        &RenderJob {
            resume: true,
            ..whole.clone()
        },
        &(),
    )
    .unwrap();
    assert!(!state.exists(), "a finished render removes its own state");
    let merged = commands::merge(
        &MergeJob {
            partials: shards,
            output: Some(out.clone()),
            allow_missing: false,
        },
        &(),
    )
    .unwrap();
    assert!(!merged.incomplete);
    assert_eq!(
        std::fs::read(&out).unwrap(),
        std::fs::read(dir.join("k.exr")).unwrap()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Stops a render once it has finished `0` passes (an interrupt after them).
struct StopAfterPasses(u32, std::sync::atomic::AtomicBool);

impl Observer for StopAfterPasses {
    fn pass_done(
        &self,
        passes: u32,
        _: &dyn Fn() -> grinlight::film::Film,
    ) -> grinlight::error::Result<()> {
        if passes >= self.0 {
            self.1.store(true, std::sync::atomic::Ordering::SeqCst);
        }
        Ok(())
    }
    fn stop_requested(&self) -> bool {
        self.1.load(std::sync::atomic::Ordering::SeqCst)
    }
}

/// A render with a target error, interrupted after 14 passes and resumed, stops where the
/// uninterrupted render stops — the error judged on all its passes, not the resumed ones
/// alone — with the same EXR byte for byte; interrupted at the pass that met the target and
/// resumed, it renders no pass more.
#[test]
fn a_resumed_render_with_a_target_error_stops_where_one_run_would() {
    let dir = workspace("target-resume");
    let job = |output: &str| {
        let mut job = RenderJob {
            output: Some(dir.join(output)),
            ..cornell(&dir)
        };
        job.overrides.set(&TARGET_ERROR, 0.3);
        job.overrides.unset(&PASSES);
        job
    };
    let whole = commands::render(&job("whole.exr"), &()).unwrap();
    let passes = whole.film.as_ref().unwrap().passes;
    assert!(passes > 20, "{passes}");
    let stop = StopAfterPasses(14, Default::default());
    let cut = commands::render(&job("cut.exr"), &stop).unwrap();
    assert_eq!(cut.film.as_ref().unwrap().passes, 14);
    let resumed = commands::render(
        &RenderJob {
            resume: true,
            ..job("cut.exr")
        },
        &(),
    )
    .unwrap();
    assert_eq!(resumed.film.as_ref().unwrap().passes, passes);
    assert_eq!(
        std::fs::read(dir.join("whole.exr")).unwrap(),
        std::fs::read(dir.join("cut.exr")).unwrap()
    );
    // Interrupted at the very pass that met the target, the render saved its state: resumed,
    // it finds the target met and renders no pass more.
    let stop = StopAfterPasses(passes, Default::default());
    commands::render(&job("late.exr"), &stop).unwrap();
    let resumed = commands::render(
        &RenderJob {
            resume: true,
            ..job("late.exr")
        },
        &(),
    )
    .unwrap();
    assert_eq!(resumed.film.as_ref().unwrap().passes, passes);
    assert_eq!(
        std::fs::read(dir.join("whole.exr")).unwrap(),
        std::fs::read(dir.join("late.exr")).unwrap()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

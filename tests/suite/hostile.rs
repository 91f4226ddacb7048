//! Hostile and malformed campaigns (issue 8): every fixture in `tests/campaigns/bad/` is refused
//! with an error that names the file and the field, and fuzzing the parser with random text and
//! random campaigns never panics, never hangs and never lets an unusable run through. Nothing
//! here simulates: the parser and the stability check (`plan::parse`) only.

use mdsolids::plan;
use mdsolids::spec::{Campaign, RunSpec, SpecError};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc;
use std::time::Duration;

/// The refused fixtures, `tests/campaigns/bad/`.
fn bad() -> PathBuf {
    crate::common::repo().join("tests/campaigns/bad")
}

/// The shipped campaigns' folder, `campaigns/`.
fn shipped_folder() -> PathBuf {
    crate::common::repo().join("campaigns")
}

/// A hang guard, not a speed test: every case here parses in well under a second.
const HANG_GUARD: Duration = Duration::from_secs(10);

/// `parse(file, text)` on its own thread: `Err` with a description if it panicked or has not
/// returned within [`HANG_GUARD`].
fn guarded<T: Send + 'static>(
    text: String,
    parse: fn(&str, &str) -> Result<T, SpecError>,
) -> Result<Result<T, SpecError>, String> {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(parse("fuzz.yaml", &text));
    });
    match receive.recv_timeout(HANG_GUARD) {
        Ok(result) => Ok(result),
        Err(mpsc::RecvTimeoutError::Timeout) => Err(format!("no answer within {HANG_GUARD:?}")),
        Err(mpsc::RecvTimeoutError::Disconnected) => Err("the parser panicked".into()),
    }
}

/// The fixtures: (campaign, expected-message file), sorted by name.
fn fixtures() -> Vec<(PathBuf, PathBuf)> {
    let mut found: Vec<(PathBuf, PathBuf)> = std::fs::read_dir(bad())
        .expect("tests/campaigns/bad exists")
        .map(|entry| entry.expect("a readable directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "yaml"))
        .map(|path| (path.clone(), path.with_extension("expected")))
        .collect();
    found.sort();
    found
}

#[test]
fn every_bad_fixture_is_refused_naming_the_file_and_the_field() {
    let fixtures = fixtures();
    assert!(fixtures.len() >= 20, "only {} fixtures in {}", fixtures.len(), bad().display());
    let mut failures = Vec::new();
    for (campaign, expected) in &fixtures {
        let file = campaign.display().to_string();
        let wanted = std::fs::read_to_string(expected).unwrap_or_else(|_| panic!("{} is missing", expected.display()));
        let wanted: Vec<&str> = wanted.lines().filter(|line| !line.trim().is_empty()).collect();
        assert!(!wanted.is_empty(), "{} names no expected text", expected.display());
        let text = std::fs::read_to_string(campaign).expect("fixtures are UTF-8");
        let file_for_thread = file.clone();
        let (send, receive) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = send.send(plan::parse(&file_for_thread, &text).map(|p| p.campaign.runs.len()));
        });
        let message = match receive.recv_timeout(HANG_GUARD) {
            Ok(Err(e)) => e.to_string(),
            Ok(Ok(runs)) => format!("(accepted, {runs} runs)"),
            Err(e) => format!("(no answer: {e:?})"),
        };
        let missing: Vec<&&str> = wanted.iter().filter(|w| !message.contains(*w)).collect();
        if !message.starts_with(&format!("{file}: ")) || !missing.is_empty() {
            failures.push(format!("{file}\n  missing {missing:?}\n  got: {message}"));
        }
    }
    assert!(failures.is_empty(), "{} of {} fixtures:\n{}", failures.len(), fixtures.len(), failures.join("\n"));
}

/// Guards issue 31, item 12: `name: y` (or n, yes, no, on, off) was accepted, though YAML
/// 1.1 readers see a boolean there; unquoted it is now refused naming the field and suggesting
/// quotes (as in the fixtures `name-boolean`, `scene-name-boolean`), and quoted it is a name.
#[test]
fn boolean_words_are_names_only_when_quoted() {
    let yaml = |name: &str, scene: &str| {
        format!("version: 1\nname: {name}\nscenes:\n  - name: {scene}\n    kind: pair\n    v0: 1.0\n")
    };
    let refused = mdsolids::spec::parse("b.yaml", &yaml("yes", "s")).unwrap_err().to_string();
    assert!(refused.starts_with("b.yaml: name = yes: YAML reads an unquoted yes as the boolean true"), "{refused}");
    assert!(refused.ends_with("quote it: name: \"yes\""), "{refused}");
    let campaign = mdsolids::spec::parse("b.yaml", &yaml("\"yes\"", "'off'")).unwrap();
    assert_eq!((campaign.name.as_str(), campaign.scenes[0].0.as_str()), ("yes", "off"));
}

/// The binary refuses a campaign whose name climbs out of `--reports` before it writes
/// anything, in `plan` and in `run`.
#[test]
fn the_binary_writes_nothing_for_a_hostile_campaign() {
    for fixture in ["name-parent", "name-absolute", "scene-name-parent", "enormous-grid"] {
        for command in ["plan", "run"] {
            let work = crate::common::scratch();
            let reports = work.path().join("reports");
            let campaign = bad().join(format!("{fixture}.yaml"));
            let output = Command::new(crate::common::MDSOLIDS)
                .current_dir(work.path())
                .arg("--reports")
                .arg(&reports)
                .arg(command)
                .arg(&campaign)
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(!output.status.success(), "{command} {fixture} succeeded");
            assert!(stderr.contains(&campaign.display().to_string()), "{command} {fixture}: {stderr}");
            let written: Vec<_> = std::fs::read_dir(work.path()).unwrap().collect();
            assert!(written.is_empty(), "{command} {fixture} wrote {written:?}");
        }
        assert!(!Path::new("/tmp/escape").exists(), "{fixture} escaped to /tmp/escape");
    }
}

/// A grid over the limit is refused with its count before it is expanded, and one at the
/// limit is not refused for its size.
#[test]
fn the_run_limit_counts_before_expanding() {
    let values = |n: usize| (1..=n).map(|i| format!("{}", i as f64 / 1000.0)).collect::<Vec<_>>().join(", ");
    let campaign = |a: usize, b: usize| {
        format!(
            "version: 1\nname: t\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n    grid:\n      v0: [{}]\n      \
             material.mass: [{}]\n",
            values(a),
            values(b)
        )
    };
    let error = mdsolids::spec::parse("big.yaml", &campaign(1001, 100)).unwrap_err().to_string();
    assert!(error.contains("scenes[0].grid: 100100 runs (material.mass: 100 values × v0: 1001 values)"), "{error}");
    assert!(error.contains(&format!("at most {} runs", mdsolids::spec::MAX_RUNS)), "{error}");
    assert_eq!(mdsolids::spec::parse("ok.yaml", &campaign(10, 10)).unwrap().runs.len(), 100);
    // The campaign `plan` is timed on (docs/guarantees.md, "Budgets"): 400 × 250, exactly at the limit.
    let at_limit = mdsolids::spec::load(&crate::common::repo().join("tests/campaigns/plan-100k.yaml")).unwrap();
    assert_eq!(at_limit.runs.len() as u64, mdsolids::spec::MAX_RUNS);
}

/// Numbers equal in value give one run id however they are written (`50` or `50.0`, `0.0` or
/// `-0.0`), in a grid or in the scene itself, and the grid column shows them one way; the
/// stored results of one are the results of the other.
#[test]
fn equal_numbers_written_differently_give_one_run_id() {
    let campaign = |dt: &str, background: &str, gamma: &str| {
        format!(
            "version: 1\nname: t\nscenes:\n  - name: p\n    kind: pair\n    v0: 1.0\n    damping: {{gamma: {gamma}}}\n    \
             grid:\n      time.dt_per_tc: [{dt}]\n      damping.background: [{background}]\n"
        )
    };
    let run = |dt, background, gamma| plan::parse("same.yaml", &campaign(dt, background, gamma)).unwrap().campaign.runs;
    let (plain, written_otherwise) = (run("50", "0", "0.0"), run("50.0", "-0.0", "-0.0"));
    assert_eq!(plain[0].run_id(), written_otherwise[0].run_id());
    assert_eq!(plain[0].varied, written_otherwise[0].varied);
    assert_eq!(written_otherwise[0].varied_label(|_| true), "background=0, dt_per_tc=50");
    assert_ne!(plain[0].run_id(), run("50", "0", "0.001")[0].run_id(), "a different value is another run");
}
// ---------------------------------------------------------------------------------------------
// Fuzzing. Cases per test are set explicitly, 3 800 together (a few seconds: the suite is sized
// to build and run in about 80 s on 2 cores, docs/performance.md, "Build and test times"); proptest draws new
// cases on every run. For a deeper search set proptest's own variable, which then replaces every
// count: `PROPTEST_CASES=50000 cargo test --release --test suite hostile::`.

const RANDOM_TEXT_CASES: u32 = 1000;
const MUTATION_CASES: u32 = 1000;
const TOKEN_SOUP_CASES: u32 = 800;
const STRUCTURED_CASES: u32 = 1000;

fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|n| n.parse().ok()).unwrap_or(cases);
    ProptestConfig { cases, ..ProptestConfig::default() }
}

/// Parses `text` with the stability check and, when it is accepted, checks every run.
fn assert_refused_or_sane(text: String) -> Result<(), TestCaseError> {
    match guarded(text, plan::parse) {
        Err(problem) => Err(TestCaseError::fail(problem)),
        Ok(Err(e)) => {
            let message = e.to_string();
            prop_assert!(message.starts_with("fuzz.yaml: "), "the error does not name the file: {}", message);
            Ok(())
        }
        Ok(Ok(plan)) => check_sane(&plan.campaign),
    }
}

/// What every accepted run must satisfy before it may start.
fn check_sane(campaign: &Campaign) -> Result<(), TestCaseError> {
    prop_assert!(!campaign.runs.is_empty() && campaign.runs.len() as u64 <= mdsolids::spec::MAX_RUNS);
    for spec in &campaign.runs {
        let RunSpec { mass, k, spacing, t_c, dt, duration, steps, samples, gamma, gamma_background, v0, .. } = *spec;
        let positive =
            [("mass", mass), ("k", k), ("spacing", spacing), ("t_c", t_c), ("dt", dt), ("duration", duration)];
        for (what, value) in positive {
            prop_assert!(value.is_finite() && value > 0.0, "{} = {} in {:?}", what, value, spec);
        }
        for (what, value) in [("gamma", gamma), ("gamma_background", gamma_background), ("v0", v0)] {
            prop_assert!(value.is_finite() && value >= 0.0, "{} = {} in {:?}", what, value, spec);
        }
        prop_assert!((1..=2_000_000_000).contains(&steps), "steps = {} in {:?}", steps, spec);
        prop_assert!(samples >= 2);
        prop_assert!(spec.chain().is_none_or(|c| (1..=100_000).contains(&c.n)));
        if let Some(l) = spec.lattice() {
            prop_assert!((2..=2000).contains(&l.nx) && (2..=2000).contains(&l.ny));
        }
    }
    Ok(())
}

/// The shipped campaigns, small ones first.
fn shipped() -> Vec<String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(shipped_folder())
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "yaml"))
        .collect();
    files.sort_by_key(|path| std::fs::metadata(path).map(|m| m.len()).unwrap_or(0));
    files.iter().map(|path| std::fs::read_to_string(path).unwrap()).collect()
}

/// One random edit of a text, at a position given as a fraction of its length.
#[derive(Clone, Debug)]
enum Edit {
    Delete(f64, usize),
    Insert(f64, String),
    Duplicate(f64, usize),
    Swap(f64, f64),
}

fn edit() -> BoxedStrategy<Edit> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), 1..40usize).prop_map(|(at, n)| Edit::Delete(at, n)),
        (at.clone(), token()).prop_map(|(at, t)| Edit::Insert(at, t)),
        (at.clone(), 1..200usize).prop_map(|(at, n)| Edit::Duplicate(at, n)),
        (at.clone(), at).prop_map(|(a, b)| Edit::Swap(a, b)),
    ]
    .boxed()
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    let index = |at: f64, len: usize| ((at * len as f64) as usize).min(len);
    for edit in edits {
        let len = chars.len();
        match edit {
            Edit::Delete(at, n) => {
                let start = index(*at, len);
                chars.drain(start..(start + n).min(len));
            }
            Edit::Insert(at, token) => {
                let start = index(*at, len);
                chars.splice(start..start, token.chars());
            }
            Edit::Duplicate(at, n) => {
                let start = index(*at, len);
                let copy: Vec<char> = chars[start..(start + n).min(len)].to_vec();
                chars.splice(start..start, copy);
            }
            Edit::Swap(a, b) if len > 0 => chars.swap(index(*a, len - 1), index(*b, len - 1)),
            Edit::Swap(..) => {}
        }
    }
    chars.into_iter().collect()
}

/// YAML syntax: brackets, indentation, anchors, tags, block scalars, documents, quotes and
/// stray bytes.
const YAML_SYNTAX: &[&str] = &[
    "{",
    "}",
    "[",
    "]",
    ":",
    ": ",
    ",",
    "- ",
    "\n",
    "\n  ",
    "\n    ",
    "  ",
    "\t",
    "&a ",
    "*a",
    "&b ",
    "*b",
    "<<: *a",
    "!!str ",
    "!!float ",
    "!!map ",
    "!tag ",
    "? ",
    "|\n",
    ">-\n",
    "'",
    "\"",
    "#",
    "---\n",
    "...\n",
    "%YAML 1.2\n",
    "\\",
    "\0",
    "\u{feff}",
];

/// Keys and words of a campaign.
const CAMPAIGN_KEYS: &[&str] = &[
    "version: 1\n",
    "name: ",
    "scenes:",
    "defaults:",
    "grid:",
    "kind: ",
    "pair",
    "chain",
    "lattice",
    "v0: ",
    "n: ",
    "material: ",
    "mass: ",
    "k: ",
    "time: ",
    "dt_per_tc: ",
    "dt: ",
    "samples: ",
    "lattice: ",
    "size: ",
    "nx: ",
    "ny: ",
    "duration_tc: ",
    "damping: ",
    "restitution: ",
    "gamma: ",
    "density: ",
    "law: power",
    "beta: ",
    "contact: true",
    "relax: {}",
    "wall_distance: ",
];

/// Values at and past the edges: paths, non-finite and huge numbers, other bases, nulls,
/// booleans and text.
const HOSTILE_VALUES: &[&str] = &[
    "..",
    "/",
    "../",
    ".nan",
    ".inf",
    "-.inf",
    "0",
    "-1",
    "1e308",
    "1e-308",
    "1e400",
    "-0",
    "0x7f",
    "0o17",
    "18446744073709551616",
    "2000",
    "2001",
    "100000",
    "null",
    "~",
    "true",
    "yes",
    "é",
    "\u{202e}",
];

/// YAML syntax, campaign keys and hostile values, and random numbers and names.
fn token() -> BoxedStrategy<String> {
    let fixed = [YAML_SYNTAX, CAMPAIGN_KEYS, HOSTILE_VALUES].concat();
    prop_oneof![
        proptest::sample::select(fixed).prop_map(str::to_string),
        any::<f64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        "[a-z_.]{1,12}",
    ]
    .boxed()
}

proptest! {
    #![proptest_config(config(RANDOM_TEXT_CASES))]
    /// Random bytes (read as UTF-8 with replacement characters).
    #[test]
    fn random_text_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
        assert_refused_or_sane(String::from_utf8_lossy(&bytes).into_owned())?;
    }
}

proptest! {
    #![proptest_config(config(MUTATION_CASES))]
    /// Random edits of the shipped campaigns. The large ones are mutated through the spec
    /// layer only: their stability check takes seconds (one Lanczos eigenvalue estimate per lattice run).
    #[test]
    fn mutated_campaigns_never_panic(
        which in 0..5usize,
        edits in proptest::collection::vec(edit(), 1..6),
    ) {
        let files = shipped();
        let text = apply(&files[which % files.len()], &edits);
        if which == 0 {
            assert_refused_or_sane(text)?;
        } else {
            match guarded(text, mdsolids::spec::parse) {
                Err(problem) => return Err(TestCaseError::fail(problem)),
                Ok(Err(e)) => prop_assert!(e.to_string().starts_with("fuzz.yaml: ")),
                Ok(Ok(_)) => {}
            }
        }
    }
}

proptest! {
    #![proptest_config(config(TOKEN_SOUP_CASES))]
    /// Random sequences of YAML syntax, keys and values.
    #[test]
    fn token_soup_never_panics(tokens in proptest::collection::vec(token(), 0..80)) {
        assert_refused_or_sane(tokens.concat())?;
    }
}

/// A number as YAML text: usually in the plausible range `good`, sometimes of any sign and size,
/// sometimes hostile.
fn number(good: std::ops::Range<f64>) -> BoxedStrategy<String> {
    prop_oneof![
        12 => good.prop_map(|x| format!("{x}")),
        1 => proptest::sample::select(vec![
            "0", "-0", "-1", "1", "2", "0.5", "1e-12", "-1e-300", "1e-300", "1e300", "1e308", "-1e308", "1e-320",
            ".nan", ".NaN", ".inf", "-.inf", "1e400", "18446744073709551616", "99999999999999999999999", "2000000001",
            "\"1.0\"", "one", "[]", "{}", "null", "true",
        ])
        .prop_map(str::to_string),
        1 => any::<f64>().prop_map(|x| format!("{x:e}")),
    ]
    .boxed()
}

/// A count in `good` (small, so the stability check stays quick) or a hostile one.
fn count(good: std::ops::Range<u32>) -> BoxedStrategy<String> {
    prop_oneof![
        12 => good.prop_map(|n| n.to_string()),
        1 => proptest::sample::select(vec![
            "0", "-1", "-3", "2001", "100001", "4294967296", "18446744073709551615", "1e300", "2.5", ".nan", "x",
        ])
        .prop_map(str::to_string),
    ]
    .boxed()
}

/// An enum value: usually one of `words`, sometimes a wrong one.
fn word(words: &'static [&'static str]) -> BoxedStrategy<String> {
    prop_oneof![
        12 => proptest::sample::select(words).prop_map(str::to_string),
        1 => proptest::sample::select(vec!["", "PAIR", "0", "[pair]", "{a: 1}", "null", "../x"]).prop_map(str::to_string),
    ]
    .boxed()
}

/// `key: value, ` with probability `p`, else nothing.
fn field(p: f64, key: &'static str, value: impl Strategy<Value = String> + 'static) -> BoxedStrategy<String> {
    proptest::option::weighted(p, value).prop_map(move |v| v.map_or(String::new(), |v| format!("{key}: {v}, "))).boxed()
}

/// `{a, b, ...}` from fields that each end in ", ".
fn flow_map(fields: &[String]) -> String {
    format!("{{{}}}", fields.concat()).replace(", }", "}")
}

/// The fields every kind of scene has: material, time, damping, geometry and a small grid.
fn common_fields() -> BoxedStrategy<String> {
    let material = (
        field(0.3, "mass", number(0.1..10.0)),
        field(0.3, "k", number(0.1..10.0)),
        field(0.1, "law", word(&["linear", "power", "hertz"])),
        field(0.1, "beta", number(1.0..3.0)),
    )
        .prop_map(|(a, b, c, d)| flow_map(&[a, b, c, d]))
        .boxed();
    let time = (
        field(0.2, "integrator", word(&["position-verlet", "velocity-verlet", "rk4", "gear"])),
        field(0.3, "dt_per_tc", number(20.0..100.0)),
        field(0.05, "dt", number(0.001..0.1)),
        field(0.05, "dt_omega_max", number(0.05..1.0)),
        field(0.3, "duration_tc", number(0.5..20.0)),
        field(0.2, "samples", count(2..500)),
    )
        .prop_map(|(a, b, c, d, e, f)| flow_map(&[a, b, c, d, e, f]))
        .boxed();
    let damping = (
        field(0.2, "restitution", number(0.05..1.0)),
        field(0.1, "gamma", number(0.0..0.5)),
        field(0.1, "background", number(0.0..0.5)),
    )
        .prop_map(|(a, b, c)| flow_map(&[a, b, c]))
        .boxed();
    let geometry = (field(0.3, "spacing", number(0.1..10.0)), field(0.2, "depth", number(0.1..10.0)))
        .prop_map(|(a, b)| flow_map(&[a, b]))
        .boxed();
    let grid = proptest::collection::vec(
        (
            proptest::sample::select(vec!["v0", "material.mass", "material.k", "time.dt_per_tc", "bogus"]),
            proptest::collection::vec(number(1.0..50.0), 0..4),
        ),
        1..3,
    )
    .prop_map(|axes| {
        let axes: Vec<String> =
            axes.iter().map(|(path, values)| format!("{path}: [{}], ", values.join(", "))).collect();
        flow_map(&axes)
    })
    .boxed();
    (
        field(0.5, "material", material),
        field(0.5, "time", time),
        field(0.3, "damping", damping),
        field(0.2, "geometry", geometry),
        field(0.2, "grid", grid),
    )
        .prop_map(|(a, b, c, d, e)| [a, b, c, d, e].concat())
        .boxed()
}

/// A scene of a random kind with mostly plausible and sometimes hostile fields; sometimes a
/// field of another kind.
fn scene() -> BoxedStrategy<String> {
    let pair = (field(0.95, "v0", number(0.1..5.0)), field(0.2, "material", Just("{contact: true}".to_string())))
        .prop_map(|(v0, contact)| format!("kind: pair, {v0}{contact}"))
        .boxed();
    let chain = (
        field(0.95, "n", count(1..12)),
        field(0.95, "v0", number(0.1..5.0)),
        field(0.2, "node", word(&["first", "last", "centre", "3"])),
        field(0.1, "wave", Just("{}".to_string())),
    )
        .prop_map(|(n, v0, node, wave)| format!("kind: chain, {n}{v0}{node}{wave}"))
        .boxed();
    let lattice = (
        field(0.9, "size", count(2..6)),
        field(0.1, "nx", count(2..6)),
        field(0.2, "supports", word(&["coursework", "clamped-bottom", "periodic-x", "free", "periodic-x-free"])),
        field(0.1, "relax", word(&["{max_tc: 50}", "{max_tc: 50, method: fire, preconditioner: stiffness}"])),
    )
        .prop_map(|(size, nx, supports, relax)| {
            format!("kind: lattice, lattice: {}, {supports}{relax}", flow_map(&[size, nx]))
        })
        .boxed();
    let stray =
        (word(&["pair", "chain", "lattice"]), field(0.5, "n", count(1..5)), field(0.5, "gap", number(0.0..1.0)))
            .prop_map(|(kind, n, gap)| format!("kind: {kind}, {n}{gap}"))
            .boxed();
    (prop_oneof![3 => pair, 3 => chain, 3 => lattice, 1 => stray], common_fields())
        .prop_map(|(own, common)| format!("{{{}}}", format!("{own}{common}").trim_end_matches(", ")))
        .boxed()
}

/// A whole campaign of one or two random scenes, usually named well.
fn campaign() -> BoxedStrategy<String> {
    (
        prop_oneof![4 => Just("fuzz".to_string()), 1 => "[ -~]{0,12}".prop_map(|s| format!("{s:?}"))],
        proptest::collection::vec(scene(), 1..3),
    )
        .prop_map(|(name, scenes)| {
            let scenes: String =
                scenes.iter().enumerate().map(|(i, s)| format!("  - {{name: s{i}, {}\n", &s[1..])).collect();
            format!("version: 1\nname: {name}\nscenes:\n{scenes}")
        })
        .boxed()
}

proptest! {
    #![proptest_config(config(STRUCTURED_CASES))]
    /// Whole campaigns with random field values: refused with the file named, or every run is
    /// finite and within its limits.
    #[test]
    fn structured_campaigns_are_refused_or_sane(text in campaign()) {
        assert_refused_or_sane(text)?;
    }
}

/// The structured fuzz reaches the end of the resolver: a fair share of its campaigns is
/// accepted, so the checks on accepted runs above are exercised, not only the refusals.
#[test]
fn structured_campaigns_are_often_valid() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = campaign();
    let samples = 300;
    let accepted = (0..samples)
        .filter(|_| plan::parse("fuzz.yaml", &strategy.new_tree(&mut runner).unwrap().current()).is_ok())
        .count();
    assert!(accepted * 20 >= samples, "only {accepted} of {samples} random campaigns accepted");
}

/// [`guarded`] itself reports a panic instead of passing it by.
#[test]
fn the_guard_reports_a_panic() {
    fn panics(_: &str, _: &str) -> Result<(), SpecError> {
        panic!("on purpose")
    }
    assert_eq!(guarded(String::new(), panics).err().as_deref(), Some("the parser panicked"));
}

// ---------------------------------------------------------------------------------------------
// Hostile text in the reports, unbounded inputs and options (issue 14, items 5 and 8).

/// Runs the binary in `dir` with `args`, killing it after [`HANG_GUARD`]: (success, stdout,
/// stderr), or a panic naming the command if it had to be killed.
fn binary(dir: &Path, args: &[&str]) -> (bool, String, String) {
    guarded_binary(Command::new(crate::common::MDSOLIDS).args(args), dir, args)
}

/// [`binary`] with the process's address space limited to 4 GB (`ulimit -v`): where a file
/// could be read without bound, the test fails by a failed allocation, not by taking the
/// machine's memory.
fn binary_in_4_gb(dir: &Path, args: &[&str]) -> (bool, String, String) {
    let limited = r#"ulimit -v 4000000 && exec "$0" "$@""#;
    guarded_binary(Command::new("sh").args(["-c", limited, crate::common::MDSOLIDS]).args(args), dir, args)
}

/// Runs `command` in `dir` as [`binary`] does; `args` name it in a panic.
fn guarded_binary(command: &mut Command, dir: &Path, args: &[&str]) -> (bool, String, String) {
    let mut child = command
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > HANG_GUARD {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("mdsolids {args:?} did not end within {HANG_GUARD:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    let text = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    (out.status.success(), text(&out.stdout), text(&out.stderr))
}

/// The cells of every row of the HTML table that follows `heading` in `html`.
fn table_rows_after(html: &str, heading: &str) -> Vec<usize> {
    // The last mention: the contents list names the heading before its section.
    let start = html.rfind(heading).unwrap_or_else(|| panic!("{heading} missing from {html}"));
    let table = &html[start..];
    let table = &table[..table.find("</table>").expect("the table ends")];
    table.split("<tr>").skip(1).map(|row| row.matches("<td").count() + row.matches("<th").count()).collect()
}

/// A campaign's title and description, and a stored run's status and message, reach
/// `report.md` and `index.html` as text: no live tag, no new table column or row, no block.
/// Before the Markdown autoescape the `<script>` elements ran in `index.html` and the message's
/// `|` and line break split its table row.
#[test]
fn hostile_text_stays_text_in_the_report() {
    let work = crate::common::scratch();
    let yaml = "version: 1\nname: hostile\n\
                title: \"T <script>alert(1)</script> | *x* [l](javascript:y)\"\n\
                description: \"<script>alert(2)</script>\\n\\n- not a list | cell\\n# not a heading\\n\\n<img src=x onerror=alert(3)>\"\n\
                scenes:\n  - name: pair\n    kind: pair\n    v0: 1.0\n";
    std::fs::write(work.path().join("hostile.yaml"), yaml).unwrap();
    let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "run", "hostile.yaml"]);
    assert!(ok, "{stderr}");
    // A stored record whose status and message carry markup (a tampered or foreign store).
    let runs = work.path().join("r/hostile/runs");
    let record = std::fs::read_dir(&runs)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "json"));
    let record = record.expect("a stored record");
    let mut json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&record).unwrap()).unwrap();
    json["status"] = "unstable".into();
    json["message"] = "<script>alert(4)</script> | `x\n| y | z |\n<b>bold</b>".into();
    std::fs::write(&record, serde_json::to_vec(&json).unwrap()).unwrap();
    let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "report", "hostile.yaml"]);
    assert!(ok, "{stderr}");

    // Both pages: the main one and, where the report answers coursework items, its appendix.
    let appendix = std::fs::read_to_string(work.path().join("r/hostile/appendix.html")).unwrap_or_default();
    let html = std::fs::read_to_string(work.path().join("r/hostile/index.html")).unwrap() + &appendix;
    // (The report has emphasis and lists of its own: the title's `*x*` and the description's
    // `- not a list` must not become one.)
    for live in ["<script", "<img", "<b>", "<em>x</em>", "<a href=\"javascript", "<li>not a list", "<h1>T <", "<h1>not"]
    {
        assert!(!html.contains(live), "{live} is live in index.html:\n{html}");
    }
    assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt; | *x* [l](javascript:y)"), "{html}");
    assert!(html.contains("&lt;script&gt;alert(4)&lt;/script&gt; | `x | y | z | &lt;b&gt;bold&lt;/b&gt;"), "{html}");
    // The failures table: a header and one row, three cells each.
    assert_eq!(table_rows_after(&html, "Runs that did not end"), vec![3, 3], "{html}");
    let markdown = std::fs::read_to_string(work.path().join("r/hostile/report.md")).unwrap();
    assert!(markdown.starts_with("# T \\<script\\>"), "{markdown}");
    let row = markdown.lines().find(|l| l.contains("alert(4)")).expect("the failure row");
    assert_eq!(row.replace("\\|", "").matches('|').count(), 4, "three cells: {row}");
}

/// Inputs and options that once ran out of memory, aborted or took minutes are refused at once
/// with a message naming the limit: a campaign "file" without end, a huge one, a share count
/// of 10^11 (an 800 GB allocation), 100 000 threads and a bench lattice of 10^12 nodes.
#[test]
fn unbounded_inputs_and_options_are_refused_at_once() {
    let work = crate::common::scratch();
    let big = work.path().join("big.yaml");
    std::fs::write(&big, format!("version: 1\n#{}\n", "x".repeat(2 << 20))).unwrap();
    for file in ["/dev/zero", big.to_str().unwrap()] {
        let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "plan", file]);
        assert!(
            !ok && stderr.contains(&format!("cannot read campaign file {file}: larger than 1048576 bytes")),
            "{stderr}"
        );
        assert_eq!(stderr.matches("larger than").count(), 1, "said once: {stderr}");
    }
    let smoke = shipped_folder().join("smoke.yaml");
    let smoke = smoke.to_str().unwrap();
    let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "plan", smoke, "--shard", "0/100000000000"]);
    assert!(!ok && stderr.contains("at most 100000"), "{stderr}");
    for threads in ["100000", "0"] {
        let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "run", smoke, "-j", threads]);
        assert!(!ok && stderr.contains("give a number of threads from 1 to 1024"), "{stderr}");
    }
    // A bench lattice beyond the campaigns' largest aborted on allocation (10^6 × 10^6 nodes).
    let (ok, _, stderr) = binary(work.path(), &["bench", "--n", "1000000"]);
    assert!(!ok && stderr.contains("--n 1000000: the lattice side must be in 2..=2000"), "{stderr}");
    // A kagome network needs three nodes per full row; at even N it takes N + 1 rows instead
    // of panicking on a missing top row, as it did.
    let (ok, _, stderr) = binary(work.path(), &["bench", "--n", "2", "--lattice", "kagome"]);
    assert!(!ok && stderr.contains("--n 2 --lattice kagome: must be ≥ 3"), "{stderr}");
    let (ok, stdout, stderr) = binary(
        work.path(),
        &["bench", "--n", "4", "--steps", "2", "--lattice", "kagome", "--workload", "kernel,relax", "--json"],
    );
    assert!(ok, "{stderr}");
    // 4 nodes on each of the 3 full rows, 2 + 1 on the sparse rows between them.
    assert_eq!(stdout.matches("\"particles\":15,").count(), 2, "{stdout}");
    assert!(!work.path().join("r").exists(), "nothing is written");
}

// ---------------------------------------------------------------------------------------------
// Hostile files in the store, stored text on the terminal (issue 31, items 7 and 8).

/// The smoke campaign run into `work/r`; returns its store `work/r/smoke/runs`.
fn stored_smoke(work: &Path) -> PathBuf {
    let smoke = shipped_folder().join("smoke.yaml");
    let (ok, _, stderr) = binary(work, &["--reports", "r", "run", smoke.to_str().unwrap()]);
    assert!(ok, "{stderr}");
    work.join("r/smoke/runs")
}

/// The path of the first stored record (`runs/<kind>-<hash>.json`) of `kind`.
fn stored_record(runs: &Path, kind: &str) -> PathBuf {
    let mut records: Vec<PathBuf> = std::fs::read_dir(runs).unwrap().map(|e| e.unwrap().path()).collect();
    records.sort();
    let name = |p: &PathBuf| p.file_name().unwrap().to_string_lossy().into_owned();
    records.into_iter().find(|p| name(p).starts_with(kind) && name(p).ends_with(".json")).expect("a stored record")
}

/// The series table (`series/<run_id>.parquet`) of the record at `record` (`runs/<run_id>.json`).
fn series_table_of(record: &Path) -> PathBuf {
    let folder = record.parent().and_then(Path::parent).expect("a record lies in <campaign>/runs/");
    folder.join("series").join(record.with_extension("parquet").file_name().expect("a record has a name"))
}

/// Guards issue 31, item 7: files of the store were read whole, whatever they were. A series
/// file linked to `/dev/zero` ate memory, a record that is a FIFO blocked `plan`, `report` and
/// `run` forever (`run` even past SIGTERM), and so did a FIFO as the folder's `campaign.json`.
/// Now each is a corrupt record, at once: `plan` and `report` list it with why, `run`
/// simulates it again and stores regular files in its place; the owner file is refused by name.
#[test]
fn store_files_that_are_not_regular_files_are_corrupt_at_once() {
    let work = crate::common::scratch();
    let runs = stored_smoke(work.path());
    let fifo = stored_record(&runs, "pair-");
    let chain = stored_record(&runs, "chain-");
    let zero = series_table_of(&chain);
    let make_fifo = |path: &Path| {
        std::fs::remove_file(path).unwrap();
        let name = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o644) }, 0);
    };
    make_fifo(&fifo);
    std::fs::remove_file(&zero).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let smoke = shipped_folder().join("smoke.yaml");
    let smoke = smoke.to_str().unwrap();
    // As the binary names them: under `--reports r`.
    let shown = |path: &Path| path.strip_prefix(work.path()).unwrap().display().to_string();
    let reasons = [
        (shown(&fifo), "cannot be read: a FIFO, not a regular file"),
        (shown(&chain), "its series table cannot be read: a character device, not a regular file"),
    ];
    let (ok, stdout, stderr) = binary_in_4_gb(work.path(), &["--reports", "r", "plan", smoke]);
    assert!(ok && reasons.iter().all(|(f, why)| stdout.contains(&format!("corrupt: {f} ({why})"))), "{stdout}{stderr}");
    for (command, then) in [("report", "left out of the report"), ("run", "simulated again")] {
        let (ok, _, stderr) = binary_in_4_gb(work.path(), &["--reports", "r", command, smoke]);
        let said = |(file, why): &(String, &str)| stderr.contains(&format!("{file} is corrupt ({why}); {then}"));
        assert!(ok && reasons.iter().all(said), "{command}: {stderr}");
    }
    for file in [&fifo, &chain, &zero] {
        assert!(std::fs::symlink_metadata(file).unwrap().is_file(), "{} is stored again", file.display());
    }

    let owner = work.path().join("r/smoke/campaign.json");
    make_fifo(&owner);
    let (ok, _, stderr) = binary_in_4_gb(work.path(), &["--reports", "r", "report", smoke]);
    let refused = format!("cannot read '{}': a FIFO, not a regular file", shown(&owner));
    assert!(!ok && stderr.contains(&refused), "{stderr}");
}

/// Guards issue 31, item 8: `run --reuse-other-builds` printed a record's `build` as stored,
/// and `plan` the reason a record is corrupt, which quotes the record's text: a shared store
/// could send terminal escape codes (retitle the window, clear the screen). Both are printed
/// with their control characters escaped.
#[test]
fn stored_text_reaches_the_terminal_escaped() {
    let work = crate::common::scratch();
    let runs = stored_smoke(work.path());
    let edit = |record: &Path, key: &str, value: &str| {
        let mut json: serde_json::Value = serde_json::from_slice(&std::fs::read(record).unwrap()).unwrap();
        json[key] = value.into();
        std::fs::write(record, serde_json::to_vec(&json).unwrap()).unwrap();
    };
    edit(&stored_record(&runs, "chain-"), "build", "0.1.0+x\u{1b}]0;owned\u{7}\u{1b}[2J");
    edit(&stored_record(&runs, "pair-"), "status", "\u{1b}[31mok");
    let smoke = shipped_folder().join("smoke.yaml");
    let smoke = smoke.to_str().unwrap();
    let (ok, stdout, stderr) = binary(work.path(), &["--reports", "r", "plan", smoke]);
    assert!(ok && stdout.contains("unknown variant `\\u{1b}[31mok`"), "{stdout}{stderr}");
    let (ok, _, stderr) = binary(work.path(), &["--reports", "r", "run", "--reuse-other-builds", smoke]);
    assert!(ok && stderr.contains("made by build 0.1.0+x\\u{1b}]0;owned\\u{7}\\u{1b}[2J, not by"), "{stderr}");
    for output in [&stdout, &stderr] {
        assert!(!output.contains(['\u{1b}', '\u{7}']), "a raw control character: {output:?}");
    }
}

//! Movies: a run that asks for one leaves a valid animated GIF with the requested number of
//! frames beside its record, whose colours follow the particles' speed, and the report shows it.

use mdsolids::output::Layout;
use mdsolids::plan;
use mdsolids::runner::run_campaign;
use mdsolids::sim::RunStatus;

const CAMPAIGN: &str = "version: 1\nname: film\nscenes:\n  - name: chain\n    kind: chain\n    n: 10\n    \
    node: first\n    v0: 0.1\n    movie: {frames: 12, width: 400, height: 160}\n    time: {duration_tc: 10}\n";

/// Decodes every frame of the GIF at `path` as RGBA rows of `width` pixels, as a viewer shows
/// it: the first frame whole, each later one (the box that changed, unchanged pixels
/// transparent) drawn over the picture before.
fn frames(path: &std::path::Path) -> (u16, Vec<Vec<u8>>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let (width, height) = (usize::from(decoder.width()), usize::from(decoder.height()));
    let mut picture = vec![0u8; width * height * 4];
    let mut frames: Vec<Vec<u8>> = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        if frames.is_empty() {
            assert_eq!(
                (usize::from(frame.width), usize::from(frame.height)),
                (width, height),
                "the first frame is whole"
            );
        }
        let (left, top, w) = (usize::from(frame.left), usize::from(frame.top), usize::from(frame.width));
        for (i, pixel) in frame.buffer.chunks(4).enumerate() {
            if pixel[3] > 0 {
                let at = 4 * ((top + i / w) * width + left + i % w);
                picture[at..at + 4].copy_from_slice(pixel);
            }
        }
        frames.push(picture.clone());
    }
    (width as u16, frames)
}

#[test]
fn movie_has_its_frames_and_colours_follow_the_speed() {
    let reports = crate::common::scratch();
    let planned = plan::parse("film.yaml", CAMPAIGN).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    let done = run_campaign(&planned, &layout, Some(1)).unwrap();
    let record = &done.records[0];
    let path = layout.movie_file(&record.run_id);
    let (width, frames) = frames(&path);
    assert_eq!(frames.len(), 12, "the requested number of frames");
    // At t = 0 only the first particle moves, at v0, the fastest speed of the run (energy is
    // conserved, so no particle ever moves faster): its disc is the top colour of the scale
    // (which spans the speeds after the first frame), yellow, every other disc the bottom one. Yellow pixels outside the colour bar (the right
    // 90 pixels) must therefore all lie at the left end of the chain.
    let top = mdsolids::draw::speed_color(1.0);
    let is_top = |p: &[u8]| {
        (i32::from(p[0]) - i32::from(top.0)).abs() < 40
            && (i32::from(p[1]) - i32::from(top.1)).abs() < 40
            && (i32::from(p[2]) - i32::from(top.2)).abs() < 60
    };
    let hot_columns = |frame: &[u8]| -> Vec<usize> {
        frame
            .chunks(4)
            .enumerate()
            .filter(|(_, p)| is_top(p))
            .map(|(i, _)| i % width as usize)
            .filter(|&x| x + 90 < width as usize)
            .collect()
    };
    let first = hot_columns(&frames[0]);
    assert!(!first.is_empty(), "the moving particle is drawn in the top colour");
    assert!(first.iter().all(|&x| x < 60), "only the first particle is fast at t = 0: {:?}", first);
    // Later the energy has spread: no disc is at the top colour at the left end any more.
    assert!(hot_columns(&frames[6]).iter().all(|&x| x >= 60) || hot_columns(&frames[6]).is_empty());
    // The report shows the movie (the HTML pages as an image, the Markdown as a link).
    mdsolids::report::render(campaign, &layout, &done.records).unwrap();
    let link = format!("plots/{}.gif", record.run_id);
    assert!(std::fs::read_to_string(layout.file("report.md")).unwrap().contains(&format!("]({link})")));
    assert!(pages(&layout).contains(&format!("<img src=\"{link}\"")));
    the_movie_prints_as_its_filmstrip(&layout, &link, &frames);
}

/// The report's HTML: its main page and, where it has one, its appendix page.
fn pages(layout: &Layout) -> String {
    let appendix = std::fs::read_to_string(layout.file("appendix.html")).unwrap_or_default();
    std::fs::read_to_string(layout.file("index.html")).unwrap() + &appendix
}

/// On paper, the movie at `link` (whose decoded frames are `frames`) is its filmstrip: the first,
/// the last and two frames between, two to a row, 6 pixels apart, each as the GIF shows it.
fn the_movie_prints_as_its_filmstrip(layout: &Layout, link: &str, frames: &[Vec<u8>]) {
    let strip = link.replace(".gif", ".filmstrip.png");
    let html = pages(layout);
    let (width, height) = (400, 160);
    let (strip_w, strip_h) = (2 * width + 6, 2 * height + 6);
    assert!(
        html.contains(&format!("<img src=\"{strip}\""))
            && html.contains(&format!("width=\"{strip_w}\" height=\"{strip_h}\" class=\"filmstrip\"")),
        "{html}"
    );
    let mut decoder = png::Decoder::new(std::fs::File::open(layout.file(&strip)).unwrap());
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().unwrap();
    let mut rgb = vec![0u8; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgb).unwrap();
    assert_eq!((info.width, info.height), (strip_w as u32, strip_h as u32));
    // 12 frames: 1, 5, 8 and 12 (evenly spread, rounded), counted from 1.
    for (n, k) in [0, 4, 7, 11].into_iter().enumerate() {
        let (x0, y0) = ((n % 2) * (width + 6), (n / 2) * (height + 6));
        for (y, x) in (0..height).flat_map(|y| (0..width).map(move |x| (y, x))) {
            let printed = &rgb[3 * ((y0 + y) * strip_w + x0 + x)..][..3];
            let shown = &frames[k][4 * (y * width + x)..][..3];
            assert_eq!(printed, shown, "frame {} at ({x}, {y})", k + 1);
        }
    }
}

#[test]
fn a_scene_can_show_its_runs_side_by_side() {
    let reports = crate::common::scratch();
    let yaml = "version: 1\nname: pair\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {size: 5}\n    \
                supports: free\n    impulse: {velocity: [0.0, -0.01]}\n    movie: {frames: 5, width: 300, height: 200, side_by_side: true}\n    \
                time: {integrator: velocity-verlet}\n    grid:\n      lattice.diagonals: [none, both]\n";
    let planned = plan::parse("pair.yaml", yaml).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    let done = run_campaign(&planned, &layout, Some(2)).unwrap();
    let (width, frames) = frames(&layout.side_by_side_movie("kick"));
    assert_eq!(frames.len(), 5);
    // Two panels of 300 − 90 pixels and one colour bar of 90.
    assert_eq!(width, 2 * (300 - 90) + 90);
    // The report shows the side-by-side movie alone: the runs' own movies are its panels.
    mdsolids::report::render(campaign, &layout, &done.records).unwrap();
    let report = std::fs::read_to_string(layout.file("report.md")).unwrap();
    assert!(report.contains("](plots/kick-side-by-side.gif)"), "{report}");
    for r in &campaign.runs {
        assert!(!report.contains(&format!("plots/{}.gif", r.run_id())), "the own movie of {} shown twice", r.run_id());
        assert!(!layout.movie_file(&r.run_id()).exists(), "a panel is not also written as a movie of its own");
    }
}

#[test]
fn one_run_shown_side_by_side_is_a_movie_of_one_panel() {
    // A scene of one run that asks to be shown side by side gets its one-panel movie, not
    // nothing: the rule "a run shown side by side has no movie of its own" holds for any count.
    let reports = crate::common::scratch();
    let planned = plan::parse("pair.yaml", &side_by_side_campaign("both")).unwrap();
    let layout = Layout::new(reports.path(), &planned.campaign.name);
    let done = run_campaign(&planned, &layout, Some(1)).unwrap();
    assert_eq!(frames(&layout.side_by_side_movie("kick")).0, 300);
    assert!(!layout.movie_file(&done.records[0].run_id).exists());
    mdsolids::report::render(&planned.campaign, &layout, &done.records).unwrap();
    let report = std::fs::read_to_string(layout.file("report.md")).unwrap();
    assert!(report.contains("](plots/kick-side-by-side.gif)"), "{report}");
}

#[test]
fn bonds_can_be_coloured_by_strain() {
    // A free 6 × 6 lattice whose top-right node is kicked down and to the left: the bonds it
    // pushes are compressed (blue), those it pulls stretched (red).
    let reports = crate::common::scratch();
    let yaml = |strain: bool| {
        format!(
            "version: 1\nname: strain{strain}\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {{size: 6}}\n    \
             supports: free\n    impulse: {{velocity: [-0.05, -0.1]}}\n    time: {{integrator: velocity-verlet}}\n    \
             movie: {{frames: 6, width: 400, height: 400, bond_strain: {strain}}}\n"
        )
    };
    let hues = |strain: bool| {
        let planned = plan::parse("strain.yaml", &yaml(strain)).unwrap();
        let campaign = &planned.campaign;
        let layout = Layout::new(reports.path(), &campaign.name);
        let done = run_campaign(&planned, &layout, Some(1)).unwrap();
        assert_eq!(done.records[0].status, RunStatus::Ok, "{}", done.records[0].message);
        // The report's caption says how the bonds are drawn.
        mdsolids::report::render(campaign, &layout, &done.records).unwrap();
        let caption =
            if strain { "bonds coloured by strain (red stretched, blue compressed)" } else { "bonds in grey" };
        assert!(std::fs::read_to_string(layout.file("report.md")).unwrap().contains(caption), "caption: {caption}");
        let (width, frames) = frames(&layout.movie_file(&done.records[0].run_id));
        // Pixels left of the colour bar, over all frames, that are clearly red or clearly blue.
        let inside = |i: usize| i % width as usize + 90 < width as usize;
        let count = |hue: &dyn Fn(&[u8]) -> bool| -> usize {
            frames.iter().map(|f| f.chunks(4).enumerate().filter(|(i, p)| inside(*i) && hue(p)).count()).sum()
        };
        let red = count(&|p| p[0] > 150 && p[1] < 100 && p[2] < 100);
        let blue = count(&|p| p[2] > 150 && p[0] < 100 && p[1] < 120);
        (red, blue)
    };
    let (red, blue) = hues(true);
    assert!(red > 50 && blue > 50, "stretched bonds red, compressed blue: {red} red, {blue} blue pixels");
    // Without the option the bonds are grey and the discs' colour scale (violet to yellow) has
    // no red.
    assert_eq!(hues(false).0, 0);
}

/// A free 5 × 5 lattice kicked at a corner, its runs side by side (one per `diagonals` value).
fn side_by_side_campaign(diagonals: &str) -> String {
    format!(
        "version: 1\nname: pair\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {{size: 5}}\n    \
         supports: free\n    impulse: {{velocity: [0.0, -0.01]}}\n    \
         movie: {{frames: 5, width: 300, height: 200, side_by_side: true}}\n    \
         time: {{integrator: velocity-verlet}}\n    grid:\n      lattice.diagonals: [{diagonals}]\n"
    )
}

#[test]
fn movies_lost_after_a_kill_are_drawn_again_the_same() {
    // A kill can land after the records are stored but before (or while) their movies are
    // written; the movies must come back, byte for byte (frames are re-simulated, and runs are
    // deterministic).
    let reports = crate::common::scratch();
    let planned = plan::parse("pair.yaml", &side_by_side_campaign("none, both")).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    run_campaign(&planned, &layout, Some(2)).unwrap();
    let both = std::fs::read(layout.side_by_side_movie("kick")).unwrap();
    std::fs::remove_file(layout.side_by_side_movie("kick")).unwrap();
    let again = run_campaign(&planned, &layout, Some(2)).unwrap();
    assert_eq!(again.simulated, 0, "the records are stored");
    assert_eq!(std::fs::read(layout.side_by_side_movie("kick")).unwrap(), both, "the side-by-side movie is back");
    // A run's own movie comes back the same way (a scene not shown side by side).
    let reports = crate::common::scratch();
    let planned = plan::parse("own.yaml", &side_by_side_campaign("none").replace(", side_by_side: true", "")).unwrap();
    let layout = Layout::new(reports.path(), &planned.campaign.name);
    let done = run_campaign(&planned, &layout, Some(1)).unwrap();
    let run_movie = layout.movie_file(&done.records[0].run_id);
    let one = std::fs::read(&run_movie).unwrap();
    std::fs::remove_file(&run_movie).unwrap();
    assert_eq!(run_campaign(&planned, &layout, Some(1)).unwrap().simulated, 0, "the record is stored");
    assert_eq!(std::fs::read(&run_movie).unwrap(), one, "the run's movie is back");
}

#[test]
fn a_side_by_side_movie_follows_the_runs_of_its_scene() {
    let reports = crate::common::scratch();
    let run = |diagonals: &str| {
        let planned = plan::parse("pair.yaml", &side_by_side_campaign(diagonals)).unwrap();
        let campaign = &planned.campaign;
        let layout = Layout::new(reports.path(), &campaign.name);
        run_campaign(&planned, &layout, Some(2)).unwrap();
        let movie = layout.side_by_side_movie("kick");
        (frames(&movie).0, std::fs::read(movie).unwrap())
    };
    let (width, two) = run("none, both");
    assert_eq!(width, 2 * (300 - 90) + 90);
    // A run added: the movie is drawn again with three panels.
    let (width, _) = run("none, both, rising");
    assert_eq!(width, 3 * (300 - 90) + 90);
    // Another campaign of the same name and scene (one run fewer), then the first again with
    // all its runs stored: each shows a movie of its own runs, never the other's.
    let (width, other) = run("none, rising");
    assert_eq!(width, 2 * (300 - 90) + 90);
    assert_ne!(other, two);
    assert_eq!(run("none, both").1, two);
}

#[test]
fn movies_never_write_through_a_planted_link() {
    // Earlier versions wrote `runs/<id>.gif.tmp` (a fixed name) with `File::create`, which
    // follows a symbolic link planted there and overwrites its target.
    let reports = crate::common::scratch();
    let planned = plan::parse("film.yaml", CAMPAIGN).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    let victim = reports.path().join("victim");
    std::fs::write(&victim, "precious").unwrap();
    let movie = layout.movie_file(&campaign.runs[0].run_id());
    std::fs::create_dir_all(movie.parent().unwrap()).unwrap();
    std::os::unix::fs::symlink(&victim, movie.with_extension("gif.tmp")).unwrap();
    run_campaign(&planned, &layout, Some(1)).unwrap();
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert_eq!(frames(&movie).1.len(), 12);
}

#[test]
fn a_lock_file_that_is_a_symbolic_link_is_refused() {
    let reports = crate::common::scratch();
    let planned = plan::parse("film.yaml", CAMPAIGN).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    let lock = layout.run_lock_file(&campaign.runs[0].run_id());
    std::fs::create_dir_all(lock.parent().unwrap()).unwrap();
    let elsewhere = reports.path().join("elsewhere");
    std::os::unix::fs::symlink(&elsewhere, &lock).unwrap();
    let error = format!("{:#}", run_campaign(&planned, &layout, Some(1)).unwrap_err());
    assert!(error.contains(lock.to_str().unwrap()) && error.contains("symbolic link"), "{error}");
    assert!(!elsewhere.exists(), "no file is created through the link");
}

/// Encoding a run's movie is part of the run and stops at its deadline (issue 14: a GIF encode
/// ran 131 s under a 10 s budget with status ok): a movie whose deadline has passed is not
/// written, and no temporary file is left; the runner records the run with `status = budget`.
#[test]
fn a_movie_stops_at_its_runs_deadline() {
    let planned = plan::parse("film.yaml", CAMPAIGN).unwrap();
    let campaign = &planned.campaign;
    let mut movie = crate::common::execute(&campaign.runs[0]).movie.unwrap();
    let dir = crate::common::scratch();
    let path = dir.path().join("late.gif");
    movie.deadline = std::time::Instant::now().checked_sub(std::time::Duration::from_millis(1));
    let error = mdsolids::draw::write_movie(&path, &movie).unwrap_err();
    assert!(error.is::<mdsolids::draw::PastDeadline>(), "{error}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
    // Within its deadline it is written.
    movie.deadline = Some(std::time::Instant::now() + std::time::Duration::from_secs(600));
    mdsolids::draw::write_movie(&path, &movie).unwrap();
    assert_eq!(frames(&path).1.len(), 12);
}

/// The columns (left of the colour bar) and rows (below the header: title, time,
/// magnification) of the black pixels of `frame`: what a movie draws in black there is walls
/// and held nodes.
fn black_pixels(width: u16, frame: &[u8]) -> Vec<(usize, usize)> {
    let width = usize::from(width);
    frame
        .chunks(4)
        .enumerate()
        .filter(|(_, p)| p[3] > 0 && p[0] < 30 && p[1] < 30 && p[2] < 30)
        .map(|(i, _)| (i % width, i / width))
        .filter(|&(x, y)| x + 90 < width && y > mdsolids::draw::movie::HEADER as usize)
        .collect()
}

#[test]
fn walls_and_held_nodes_are_drawn() {
    let reports = crate::common::scratch();
    // The chain between its walls: black bars at both ends.
    let planned = plan::parse("film.yaml", CAMPAIGN).unwrap();
    let layout = Layout::new(reports.path(), &planned.campaign.name);
    let done = run_campaign(&planned, &layout, Some(1)).unwrap();
    let (width, drawn) = frames(&layout.movie_file(&done.records[0].run_id));
    let black = black_pixels(width, &drawn[0]);
    let plot_width = usize::from(width) - 90;
    assert!(black.iter().filter(|(x, _)| *x < plot_width / 8).count() > 20, "a wall at the left end");
    assert!(black.iter().filter(|(x, _)| *x > plot_width * 7 / 8).count() > 20, "a wall at the right end");
    mdsolids::report::render(&planned.campaign, &layout, &done.records).unwrap();
    assert!(std::fs::read_to_string(layout.file("report.md")).unwrap().contains("walls at both ends as black bars"));

    // A lattice held at its bottom row: black squares there, nothing black above it.
    let yaml = "version: 1\nname: held\nscenes:\n  - name: kick\n    kind: lattice\n    lattice: {size: 5}\n    \
                supports: clamped-bottom\n    impulse: {velocity: [0.0, -0.01]}\n    time: {integrator: velocity-verlet}\n    \
                movie: {frames: 4, width: 300, height: 300}\n";
    let planned = plan::parse("held.yaml", yaml).unwrap();
    let layout = Layout::new(reports.path(), &planned.campaign.name);
    let done = run_campaign(&planned, &layout, Some(1)).unwrap();
    assert_eq!(done.records[0].status, RunStatus::Ok, "{}", done.records[0].message);
    let (width, drawn) = frames(&layout.movie_file(&done.records[0].run_id));
    let black = black_pixels(width, &drawn[0]);
    assert!(black.len() > 5 * 20, "five held nodes drawn in black: {} pixels", black.len());
    let lowest = black.iter().map(|(_, y)| *y).max().unwrap();
    let highest = black.iter().map(|(_, y)| *y).min().unwrap();
    assert!(lowest - highest < 30, "only the bottom row is held: black from row {highest} to {lowest}");
    mdsolids::report::render(&planned.campaign, &layout, &done.records).unwrap();
    assert!(std::fs::read_to_string(layout.file("report.md")).unwrap().contains("held nodes as black squares"));
}

/// Issue 31, item 6: a minimiser (`relax.method: fire | cg`) or the static solve has no time,
/// so its movie is two frames, the start and the state it ended in, captioned with what they
/// show. Before, `run` stopped the whole campaign at such a movie ("a movie needs at least one
/// frame"), storing nothing and naming no scene, and every rerun stopped the same way.
#[test]
fn runs_with_no_time_draw_their_start_and_end() {
    let reports = crate::common::scratch();
    let yaml = "version: 1\nname: still\nscenes:\n  - name: pair\n    kind: pair\n    v0: 1.0\n  - name: block\n    \
                kind: lattice\n    lattice: {size: 5}\n    supports: clamped-bottom\n    load: {per_node: 0.01}\n    \
                time: {integrator: velocity-verlet}\n    movie: {frames: 12, width: 300, height: 240}\n    grid:\n      \
                relax.method: [fire, cg, static]\n";
    let planned = plan::parse("still.yaml", yaml).unwrap();
    let campaign = &planned.campaign;
    let layout = Layout::new(reports.path(), &campaign.name);
    let done = run_campaign(&planned, &layout, Some(2)).expect("movies of runs with no time stop no campaign");
    for (record, method) in done.records[1..].iter().zip(["fire", "cg", "static"]) {
        assert_eq!(record.status, RunStatus::Ok, "{method}: {}", record.message);
        let (_, drawn) = frames(&layout.movie_file(&record.run_id));
        assert_eq!(drawn.len(), 2, "{method}: the start and the end, whatever movie.frames asks");
        assert_ne!(drawn[0], drawn[1], "{method}: the end is not the start (the load moved the top row)");
        let captions = crate::common::execute(&record.spec).movie.unwrap().captions;
        let end = match method {
            "static" => "static answer (relax.method: static)".to_string(),
            _ => format!("relaxed ({method}, {} force evaluations)", record.steps),
        };
        assert_eq!(captions, ["start".to_string(), end]);
    }
    mdsolids::report::render(campaign, &layout, &done.records).unwrap();
    let report = std::fs::read_to_string(layout.file("report.md")).unwrap();
    for record in &done.records[1..] {
        assert!(report.contains(&format!("](plots/{}.gif)", record.run_id)), "{report}");
    }
    assert!(report.contains("the start and the state it stopped at"), "{report}");
}

#[test]
fn a_packing_movie_draws_its_discs_to_scale_with_their_force_chains() {
    // 64 discs at φ = 0.86 relaxed by FIRE: two frames (the start and the jammed state), the
    // jammed one with its contacts as black lines (nothing else on the frame is black: the
    // discs take the load's colours, the box is red, the text is a few hundred pixels). The
    // lines' geometry and widths are checked against their formulas in the unit tests.
    let yaml = "version: 1\nname: chains\nscenes:\n  - name: jam\n    kind: packing\n    \
                packing: {n: 64, fraction: 0.86}\n    movie: {frames: 2, width: 500, height: 470}\n";
    let reports = crate::common::scratch();
    let file = reports.path().join("chains.yaml");
    std::fs::write(&file, yaml).unwrap();
    crate::common::mdsolids_ok(reports.path(), &["run", file.to_str().unwrap()]);
    let plots = reports.path().join("chains/plots");
    let gif = std::fs::read_dir(&plots)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "gif"));
    let (width, frames) = frames(&gif.expect("the packing's movie"));
    assert_eq!((width, frames.len()), (500, 2));
    let black = frames[1].chunks(4).filter(|p| p[..3] == [0, 0, 0]).count();
    assert!(black > 500, "force chains drawn: {black} black pixels");
    let report = std::fs::read_to_string(reports.path().join("chains/report.md")).unwrap();
    assert!(report.contains("every contact as a black line from centre to centre whose width grows with its force"));
}

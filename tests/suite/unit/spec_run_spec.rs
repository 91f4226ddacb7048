//! Unit tests of `src/spec/run_spec.rs`, moved out of the library (one test binary).

#[test]
fn dt_per_tc_reads_back_what_was_asked() {
    // dt = t_c/100 divided back is 99.99999999999999 for t_c = 0.9 s (and 1.8, 3.5, ...);
    // the ratio must read back exactly, whatever t_c.
    let yaml = "version: 1\nname: t\nscenes:\n  - {name: p, kind: pair, v0: 1.0, time: {dt_per_tc: 100}}\n";
    let mut spec = mdsolids::spec::parse("t.yaml", yaml).unwrap().runs.remove(0);
    for t_c in [0.9, 1.8, 3.5, spec.t_c] {
        spec.t_c = t_c;
        spec.set_dt(t_c / 100.0);
        assert_eq!(spec.dt_per_tc(), 100.0, "t_c = {t_c}");
    }
}

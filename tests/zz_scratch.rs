use cullproof::check::{self, CheckConfig};
#[test]
#[ignore]
fn scratch_write_unproven() {
    let seed: u64 = std::env::var("SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(1);
    let id = std::env::var("METHOD").unwrap();
    let all = std::env::var("WITH").unwrap_or(id.clone());
    let list: Vec<_> = all.split(',').map(|x| cullproof::args::method("--method", x, false).unwrap()).collect();
    let which = all.split(',').position(|x| x == id).unwrap();
    let ms = cullproof::bounds::shared_all(list);
    let mut cfg = CheckConfig::default_for(ms.clone());
    cfg.seed = seed;
    let dir = std::path::PathBuf::from("/tmp/unp");
    for i in 0..9600u64 {
        let (regime, case, tile) = check::make_case(&cfg, i);
        let (js, _) = check::judge(&cfg, &ms, &case, &tile, i);
        if js[which].unproven().is_empty() {
            continue;
        }
        let mut f = cullproof::corpus::CaseFile::violation(
            &id,
            (case, tile),
            &cullproof::check::Witness {
                case_index: i,
                case,
                tile,
                sample: [0.0; 5],
                bound: String::new(),
                margin: 0.0,
                embree_hit: None,
            },
            &cfg,
            ("check", i, regime.name().into()),
            vec![],
            format!("unproven {:?}", js[which].unproven()),
        );
        f.witness = None;
        f.expected = cullproof::corpus::Verdict::Conservative;
        let p = f.write_new(&dir.join(&id)).unwrap();
        println!("case {i} {regime:?} {:?} -> {:?}", js[which].unproven(), p);
    }
}

use basr::job::Job;
use basr::paint::film::{self, FilmOptions};
#[test]
fn tmp() {
    let path = std::env::var("JOB").unwrap();
    let job = Job::from_bytes(std::fs::read(&path).unwrap(), &path, None).unwrap();
    let mut o = FilmOptions::preview_defaults();
    o.preview.profile = basr::pipeline::film::job_profile(&job).unwrap();
    let m = film::film(&job, &o, &|_, _| {}).unwrap();
    let f = m.preview.film.as_ref().unwrap();
    let g = &f.grid;
    let out = f.outside.as_ref().unwrap();
    let tot: f64 = g.data.iter().sum();
    let outs: f64 = out.iter().sum();
    eprintln!(
        "outside share {:.4} grid {}x{} x0 {:.3} y0 {:.3}",
        outs / tot,
        g.nx,
        g.ny,
        g.x0,
        g.y0
    );
    let mut s = String::new();
    let maxo = out.iter().cloned().fold(0.0, f64::max);
    let sc = 4.0;
    s += &format!("<svg xmlns='http://www.w3.org/2000/svg' width='{}' height='{}'><rect width='100%' height='100%' fill='white'/>", g.nx as f64 * sc, g.ny as f64 * sc);
    for j in 0..g.ny {
        for i in 0..g.nx {
            let v = g.data[j * g.nx + i];
            let w = out[j * g.nx + i];
            let y = (g.ny - 1 - j) as f64 * sc;
            let x = i as f64 * sc;
            if w > 0.0 {
                let a = (w / maxo).sqrt();
                s += &format!("<rect x='{x}' y='{y}' width='{sc}' height='{sc}' fill='red' fill-opacity='{a:.3}'/>");
            } else if v > 0.0 {
                s += &format!("<rect x='{x}' y='{y}' width='{sc}' height='{sc}' fill='#8c8' fill-opacity='0.5'/>");
            }
        }
    }
    s += "</svg>";
    std::fs::write("/tmp/out.svg", s).unwrap();
    // column profile of outside paint
    let mut cols = vec![0.0; g.nx];
    let mut rows = vec![0.0; g.ny];
    for j in 0..g.ny {
        for i in 0..g.nx {
            cols[i] += out[j * g.nx + i];
            rows[j] += out[j * g.nx + i];
        }
    }
    for &jj in &[g.ny / 2, g.ny / 2 + 3, g.ny / 3] {
        let row: Vec<String> = (0..g.nx)
            .map(|i| {
                format!(
                    "{:.0}/{:.0}",
                    g.data[jj * g.nx + i] * 1e6,
                    out[jj * g.nx + i] * 1e6
                )
            })
            .collect();
        eprintln!(
            "ROW {jj} y={:.3}: {}",
            g.y0 + (jj as f64 + 0.5) * g.cell_m,
            row.join(" ")
        );
    }
    eprintln!(
        "cols %: {:?}",
        cols.iter()
            .map(|r| (r / outs * 1000.0).round() / 10.0)
            .collect::<Vec<_>>()
    );
    eprintln!(
        "rows %: {:?}",
        rows.iter()
            .map(|r| (r / outs * 1000.0).round() / 10.0)
            .collect::<Vec<_>>()
    );
}

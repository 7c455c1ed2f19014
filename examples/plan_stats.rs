use dlw::design::Design;
use dlw::layout::Layout;
use dlw::machine::MachineLibrary;
use dlw::process::ProcessLibrary;
use dlw::toolpath::{estimate, plan, PlanOptions};

fn main() {
    for f in ["joint-a", "joint-b", "joint-c", "joint-d"] {
        let path = format!("designs/{f}.toml");
        let d = Design::load(path.as_ref()).unwrap();
        let l = Layout::from_design(&d).unwrap();
        let sets = ProcessLibrary::beside(path.as_ref())
            .resolve(&d.file.process)
            .unwrap();
        let m = MachineLibrary::default().find(None).unwrap();
        match plan(&d, &l, &sets, &m, &PlanOptions::default()) {
            Ok(p) => {
                let aero = MachineLibrary::default()
                    .find(Some("aerotech-aerobasic"))
                    .unwrap();
                for (prof, ext) in [(&m, "ngc"), (&aero, "pgm")] {
                    let post = dlw::post::post_for(prof.dialect);
                    let text = dlw::post::write_program(&p, prof, post.as_ref()).unwrap();
                    std::fs::write(format!("/tmp/{f}.{ext}"), text).unwrap();
                }
                println!("{f}: seam {:.3}", l.seam_s_mm);
                for (op, t) in p.operations.iter().zip(&p.travel) {
                    println!(
                        "  {:?}: {} paths, travel {:.2} -> {:.2}",
                        op.kind,
                        op.paths.len(),
                        t.layout_order_mm,
                        t.planned_mm
                    );
                }
                for e in estimate(&p, &m) {
                    println!(
                        "  {:?}: beam {:.1}s rapid {:.2}s len {:.1}",
                        e.kind, e.beam_s, e.rapid_s, e.beam_length_mm
                    );
                }
            }
            Err(e) => println!("{f}: {e}"),
        }
    }
}

#[allow(dead_code)]
fn unused() {}

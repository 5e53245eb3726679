//! The Materials panel's model menu: a Lambert + Blinn-Phong material becomes metallic-roughness
//! (its Kd the base colour) and back, its sliders edit it, each change is one undo step, and the
//! hover names the material's values.

use egui::accesskit::Role;
use egui::{Key, Modifiers, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use raygine::app::RaygineApp;
use tracer_core::integrator::IntegratorKind;

type Viewer = Harness<'static, RaygineApp>;

fn material(h: &Viewer, slot: usize) -> tracer_core::scene::Material {
    h.state().document().setup.materials[slot]
}

#[test]
fn a_material_switches_to_metallic_roughness_and_back() {
    let mut h = crate::box_viewer(Vec2::new(960.0, 1000.0), IntegratorKind::Direct, 1, 0.25);
    h.get_by_label("red_wall").click();
    h.run_steps(2);
    let slot = h.state().selected_slot().expect("a slot") as usize;
    let kd = material(&h, slot).kd;
    assert!(material(&h, slot).pbr.is_none());

    h.get_by_role_and_label(Role::ComboBox, "model").click();
    h.run_steps(2);
    h.get_by_label("metallic-roughness (glTF)").click();
    h.run_steps(2);
    let p = material(&h, slot).pbr.expect("metallic-roughness");
    assert_eq!(p.base_color, kd, "Kd becomes the base colour");
    assert_eq!((p.metallic, p.roughness, p.transmission), (0.0, 1.0, 0.0));

    h.get_by_role_and_label(Role::Slider, "roughness")
        .set_value_accesskit(0.25);
    h.run_steps(2);
    h.get_by_role_and_label(Role::Slider, "metallic")
        .set_value_accesskit(1.0);
    h.run_steps(2);
    let p = material(&h, slot).pbr.expect("metallic-roughness");
    assert_eq!((p.metallic, p.roughness), (1.0, 0.25));
    let summary = raygine::panels::materials::summary(&material(&h, slot));
    assert!(
        summary.contains("metallic 1.00, roughness 0.25"),
        "{summary}"
    );

    // One undo step per change: the metallic slider, then the roughness.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(material(&h, slot).pbr.expect("still").metallic, 0.0);

    // Back to Blinn-Phong: a metal's base colour becomes Ks, roughness 0.25 a lobe of
    // glossiness 2 / 0.25⁴ − 2 = 510.
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run_steps(2);
    h.get_by_role_and_label(Role::ComboBox, "model").click();
    h.run_steps(2);
    h.get_by_label("Lambert + Blinn-Phong").click();
    h.run_steps(2);
    let m = material(&h, slot);
    assert!(m.pbr.is_none());
    assert_eq!(m.ks, kd);
    assert!((m.glossiness - 510.0).abs() < 0.1, "{}", m.glossiness);
}

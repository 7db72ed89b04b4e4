//! Evaluating one family A leg on the time grid: the sensor's world position by integrating the
//! ankle's exact velocity and acceleration on a grid [`OVERSAMPLE`] times finer than the output,
//! and at each output sample the noise-free specific force and angular velocity in the device
//! frame (gravity rotated in, the lever arm from the ankle to the sensor differentiated
//! exactly), the orientation and the true angles.

use super::super::curves::TOE_OFF;
use super::super::jet::{body_rate, mat_mul, mat_vec, rot_x, rot_y, rot_z, Jet, JetVec3};
use super::super::{DenseTruth, SubjectParams};
use super::leg::{LegModel, LegState, Shared};
use super::phase::Heading;
use super::{HALF_STEP_WIDTH_M, OVERSAMPLE};
use ldh_core::recording::STANDARD_GRAVITY_MPS2;

/// The output grid (`fs_hz` over `duration_s`, both ends included) and the integration grid
/// inside it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Grid {
    /// Output sampling rate, Hz.
    pub(super) fs_hz: f64,
    /// Output samples.
    pub(super) n_out: usize,
    /// Integration step, s (`1 / (fs_hz · OVERSAMPLE)`).
    h: f64,
    /// Integration steps (`(n_out − 1) · OVERSAMPLE + 1`).
    n_int: usize,
}

impl Grid {
    /// The grids of a subject's recording.
    pub(super) fn new(params: &SubjectParams) -> Grid {
        let fs = params.fs_hz;
        let n_out = (params.duration_s * fs).round() as usize + 1;
        let h = 1.0 / (fs * OVERSAMPLE as f64);
        let n_int = (n_out - 1) * OVERSAMPLE + 1;
        Grid {
            fs_hz: fs,
            n_out,
            h,
            n_int,
        }
    }
}

/// Truth on the integration grid, for the stride truth.
#[derive(Debug, Clone)]
pub(super) struct FineTrack {
    /// Time, s.
    pub(super) t: Vec<f64>,
    /// Shank pitch θ, deg.
    pub(super) theta_deg: Vec<f64>,
    /// Anatomical roll ρ, deg.
    pub(super) rho_deg: Vec<f64>,
    /// World (x, y) of each stride's heel contact point at its first stance step, m.
    pub(super) heel_pos: Vec<Option<[f64; 2]>>,
}

/// Everything [`evaluate`] computes for one leg.
#[derive(Debug, Clone)]
pub(super) struct LegKinematics {
    /// Noise-free device signals and world kinematics at each output sample.
    pub(super) dense: DenseTruth,
    /// Shank pitch θ at each output sample, deg.
    pub(super) pitch_deg: Vec<f64>,
    /// Anatomical roll ρ at each output sample, deg.
    pub(super) roll_deg: Vec<f64>,
    /// Heading ψ at each output sample, deg.
    pub(super) yaw_deg: Vec<f64>,
    /// Truth on the integration grid.
    pub(super) fine: FineTrack,
}

/// Rotation about the vertical by the heading ψ, and its derivative with respect to ψ.
struct HeadingRot {
    cp: f64,
    sp: f64,
}

impl HeadingRot {
    fn new(psi: f64) -> HeadingRot {
        let (cp, sp) = (psi.cos(), psi.sin());
        HeadingRot { cp, sp }
    }
    fn rot(&self, v: [f64; 3]) -> [f64; 3] {
        let (cp, sp) = (self.cp, self.sp);
        [cp * v[0] - sp * v[1], sp * v[0] + cp * v[1], v[2]]
    }
    fn rot_d(&self, v: [f64; 3]) -> [f64; 3] {
        let (cp, sp) = (self.cp, self.sp);
        [-sp * v[0] - cp * v[1], cp * v[0] - sp * v[1], 0.0]
    }
}

/// Evaluate `leg` on `grid`: the world ankle velocity v_w = R(ψ)·v and acceleration
/// a_w = R(ψ)·a plus ψ̇·R'(ψ)·v from the progression-frame ankle, the world position by the
/// trapezoid rule with end correction (h²/12 · (a₀ − a₁)), started at the ankle's first
/// position offset laterally by half the step width. `n_idx` is the length of the per-stride
/// tables.
pub(super) fn evaluate(
    leg: &LegModel,
    sh: &Shared,
    heading: &Heading,
    grid: &Grid,
    n_idx: usize,
) -> LegKinematics {
    let (n_out, n_int, h) = (grid.n_out, grid.n_int, grid.h);
    let mut out = LegKinematics::with_capacity(n_out, n_int, n_idx);
    let lateral0 = leg.lat * HALF_STEP_WIDTH_M;
    let mut world = [0.0f64; 3];
    let mut prev_v = [0.0f64; 3];
    let mut prev_a = [0.0f64; 3];
    let r_f = [
        Jet::cst(0.0),
        Jet::cst(leg.lat * leg.p.sensor_lateral_m),
        Jet::cst(leg.p.sensor_height_m),
    ];
    for i in 0..n_int {
        let t = i as f64 * h;
        let st = leg.state(sh, t);
        let psi = heading.eval(t);
        let r = HeadingRot::new(psi.v);
        let vp = [st.ankle[0].d, st.ankle[1].d, st.ankle[2].d];
        let ap = [st.ankle[0].dd, st.ankle[1].dd, st.ankle[2].dd];
        let v_w = r.rot(vp);
        let rd = r.rot_d(vp);
        let a_w: [f64; 3] = std::array::from_fn(|k| r.rot(ap)[k] + psi.d * rd[k]);
        if i == 0 {
            let p0 = [st.ankle[0].v, st.ankle[1].v + lateral0, st.ankle[2].v];
            world = r.rot(p0);
        } else {
            for k in 0..3 {
                world[k] += 0.5 * h * (prev_v[k] + v_w[k]) + h * h / 12.0 * (prev_a[k] - a_w[k]);
            }
        }
        prev_v = v_w;
        prev_a = a_w;
        out.fine.t.push(t);
        out.fine.theta_deg.push(st.theta.v.to_degrees());
        out.fine.rho_deg.push(st.rho.v.to_degrees());
        // Heel contact point of stride j in the world, at its first stance sample:
        // ankle − R(ψ)·(ankle − heel) in the progression frame.
        let qf = st.q - st.q.floor();
        let j = st.q.floor().max(0.0) as usize;
        let heel_pos = &mut out.fine.heel_pos;
        if qf < TOE_OFF && j < n_idx && heel_pos[j].is_none() && leg.x_heel[j].is_finite() {
            let rel = r.rot([st.ankle[0].v - leg.x_heel[j], st.ankle[1].v, 0.0]);
            heel_pos[j] = Some([world[0] - rel[0], world[1] - rel[1]]);
        }
        if i % OVERSAMPLE != 0 {
            continue;
        }
        let motion = Motion {
            st: &st,
            psi,
            a_w,
            v_w,
            world,
        };
        out.push_sample(leg, &motion, &r_f);
    }
    out
}

/// The leg's motion at one output sample.
struct Motion<'a> {
    st: &'a LegState,
    /// Heading ψ, rad.
    psi: Jet,
    /// Ankle acceleration in the world, m/s².
    a_w: [f64; 3],
    /// Ankle velocity in the world, m/s.
    v_w: [f64; 3],
    /// Integrated ankle position in the world, m.
    world: [f64; 3],
}

impl LegKinematics {
    fn with_capacity(n_out: usize, n_int: usize, n_idx: usize) -> LegKinematics {
        LegKinematics {
            dense: DenseTruth {
                acc_clean_g: Default::default(),
                gyro_clean_dps: Default::default(),
                sensor_pos_m: Default::default(),
                sensor_vel_mps: Default::default(),
                r_world_device: Vec::with_capacity(n_out),
                euler_rad: Default::default(),
            },
            pitch_deg: Vec::with_capacity(n_out),
            roll_deg: Vec::with_capacity(n_out),
            yaw_deg: Vec::with_capacity(n_out),
            fine: FineTrack {
                t: Vec::with_capacity(n_int),
                theta_deg: Vec::with_capacity(n_int),
                rho_deg: Vec::with_capacity(n_int),
                heel_pos: vec![None; n_idx],
            },
        }
    }

    /// Sensor kinematics at an output sample: `r_f` is the sensor's position in the anatomical
    /// frame F (lateral offset, height above the ankle), m. Specific force f = a + g (z up),
    /// rotated into F by R_wFᵀ and into the device by the mounting; angular velocity the body
    /// rate of R_wF in the device frame.
    fn push_sample(&mut self, leg: &LegModel, m: &Motion, r_f: &JetVec3) {
        let (st, psi, a_w, v_w, world) = (m.st, m.psi, m.a_w, m.v_w, m.world);
        let mount = &leg.mounting.mount;
        let d = &mut self.dense;
        let r_wf = mat_mul(&rot_z(psi), &mat_mul(&rot_y(st.theta), &rot_x(st.phi)));
        let off = mat_vec(&r_wf, r_f);
        let acc_w: [f64; 3] = std::array::from_fn(|k| a_w[k] + off[k].dd);
        let f_w = [acc_w[0], acc_w[1], acc_w[2] + STANDARD_GRAVITY_MPS2];
        let r_fv: [[f64; 3]; 3] = std::array::from_fn(|a| std::array::from_fn(|b| r_wf[a][b].v));
        // F coordinates, then device coordinates.
        let f_f: [f64; 3] = std::array::from_fn(|k| (0..3).map(|m| r_fv[m][k] * f_w[m]).sum());
        let f_d: [f64; 3] = std::array::from_fn(|k| (0..3).map(|m| mount[m][k] * f_f[m]).sum());
        let w_f = body_rate(&r_wf);
        let w_d: [f64; 3] = std::array::from_fn(|k| (0..3).map(|m| mount[m][k] * w_f[m]).sum());
        for k in 0..3 {
            d.acc_clean_g[k].push(f_d[k] / STANDARD_GRAVITY_MPS2);
            d.gyro_clean_dps[k].push(w_d[k].to_degrees());
            d.sensor_pos_m[k].push(world[k] + off[k].v);
            d.sensor_vel_mps[k].push(v_w[k] + off[k].d);
        }
        let r_wd: [[f64; 3]; 3] = std::array::from_fn(|a| {
            std::array::from_fn(|b| (0..3).map(|m| r_fv[a][m] * mount[m][b]).sum())
        });
        d.r_world_device.push(r_wd);
        d.euler_rad[0].push(st.phi.v);
        d.euler_rad[1].push(st.theta.v);
        d.euler_rad[2].push(psi.v);
        self.pitch_deg.push(st.theta.v.to_degrees());
        self.roll_deg.push(st.rho.v.to_degrees());
        self.yaw_deg.push(psi.v.to_degrees());
    }
}

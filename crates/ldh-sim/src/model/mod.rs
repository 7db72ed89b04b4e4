//! The kinematic model of one subject's two shanks and the sensors on them.
//!
//! Frames. World: X forward (initial walking direction), Y left, Z up. The shank's anatomical
//! frame F (the same for both legs): e1 anterior, e2 left, e3 along the shank upwards. Its
//! orientation is `R_wF = Rz(ψ) · Ry(θ) · Rx(φ)` (ZYX Euler angles): θ is the sagittal
//! inclination from vertical, positive when the knee is anterior to the ankle (SPEC §3.3), φ the
//! frontal inclination and ψ the heading. The anatomical roll reported as truth is ρ, positive
//! when the knee is lateral to the ankle (φ = −ρ on the left leg, +ρ on the right).
//!
//! Sensor (device) frame, paper §2.2: x along the shank (up), y anterior-posterior, z
//! medio-lateral. A device worn on the lateral side of the left shank has (x, y, z) = (e3, e1,
//! e2); the same device on the right shank faces the other way: (e3, −e1, −e2) — the mirrored
//! mounting of real recordings. On top comes a mounting misalignment: a rotation about the
//! shank axis (tens of degrees on real recordings) and small tilts.
//!
//! Motion. A continuous gait phase p(t) (a C² quintic through the heel-strike times, stride
//! durations drawn with the subject's variability) is warped to a canonical phase q in which
//! toe off is always at 0.60, so each leg's stance ratio is set by the warp. Hip and knee
//! flexion follow the normal curves ([`super::curves`]), modified per leg (less swing knee
//! flexion, smaller hip excursion on the affected side of an LDH subject); the shank
//! inclination is knee − hip flexion. The foot rolls over the heel (foot angle down to 0 at
//! 10 % of the cycle), stays flat (ankle fixed), then rolls over the forefoot until toe off;
//! the ankle therefore moves on circles about the heel and toe contact points and never slips.
//! In swing the ankle follows a quintic matching position, velocity and acceleration at toe off
//! and at the next heel strike, plus a clearance bump and a lateral (circumduction) bump. At
//! start and end the subject stands still; gait is ramped in and out over one stride. A 180°
//! turn (heading ψ ramped over two strides, shorter strides) can split the walk into two bouts;
//! during a turn the ankle's world velocity is the heading-rotated progression velocity (the
//! foot pivots about the ankle's vertical axis).
//!
//! Every quantity is a [`Jet`] of time: acceleration is the exact second derivative of the
//! sensor's position, angular velocity the exact body rate of `R_wF`.

//!
//! Code layout, in the order [`simulate_subject`] runs the steps (and draws from the subject's
//! random stream — the order of the draws fixes every simulated number): [`phase`] the
//! timeline (stride times), [`leg`] the legs (stance ratios, then stride lengths), [`events`]
//! the true events and swings, the device mountings ([`super::sensor::Mounting`]), then per
//! leg [`kinematics`] on the time grid, [`strides`] the stride truth and the measurement
//! ([`super::sensor::measure`]: biases and noise).

mod events;
mod kinematics;
mod leg;
mod phase;
mod strides;

use rand_chacha::ChaCha8Rng;

use super::curves;
pub(crate) use super::draw::{normal_clamped, std_normal};
use super::sensor::{measure, Mounting};
use super::{SensorModel, SubjectParams};
use events::LegEvents;
use kinematics::Grid;
use ldh_core::error::Result;
use ldh_core::recording::Recording;
use leg::{LegModel, Shared};
use phase::Timeline;

pub use super::truth::{DenseTruth, LegTruth, SensorTruth, SimLeg, SimSubject, StrideTruth};

const TAU: f64 = std::f64::consts::TAU;
/// Heel contact point to ankle joint, foot frame (forward, up), m.
const HEEL_TO_ANKLE: (f64, f64) = (0.05, 0.08);
/// Forefoot (MTP) contact point to ankle joint, foot frame, m.
const TOE_TO_ANKLE: (f64, f64) = (-0.15, 0.08);
/// Half the step width: lateral distance of each ankle from the line of progression, m.
const HALF_STEP_WIDTH_M: f64 = 0.09;
/// Oversampling of the internal grid used to integrate world positions.
const OVERSAMPLE: usize = 10;

/// Simulate one subject. `rng` draws stride-to-stride variability and the sensor errors.
pub fn simulate_subject(
    params: &SubjectParams,
    sensor: &SensorModel,
    rng: &mut ChaCha8Rng,
) -> Result<SimSubject> {
    params.validate()?;
    sensor.validate()?;
    let timeline = Timeline::draw(params, rng)?;
    let (knee, hip) = (curves::knee_flexion(), curves::hip_flexion());
    let sh = Shared {
        phase: &timeline.phase,
        knee: &knee,
        hip: &hip,
    };
    let mut legs = leg::build_legs(params, &timeline, rng);
    leg::place_heels(&mut legs, params, &timeline, rng);
    let mut events = Vec::with_capacity(2);
    for leg in legs.iter_mut() {
        events.push(events::leg_events(leg, &sh, timeline.n));
        leg.mounting = Mounting::draw(sensor, leg.side, rng);
    }
    let grid = Grid::new(params);
    let mut sim_legs = Vec::with_capacity(2);
    for (leg, ev) in legs.iter().zip(events) {
        sim_legs.push(simulate_leg(leg, &sh, &timeline, &grid, ev, sensor, rng)?);
    }
    let right = sim_legs.pop().expect("two legs");
    let left = sim_legs.pop().expect("two legs");
    Ok(SimSubject {
        params: params.clone(),
        left,
        right,
        family_b: None,
    })
}

/// One leg from its model to what the simulator delivers: the kinematics on `grid`, the
/// stride truth from `events`, the measured recording (at `grid.fs_hz`, biases and noise drawn
/// from `rng`) and the leg's truth.
fn simulate_leg(
    leg: &LegModel,
    sh: &Shared,
    timeline: &Timeline,
    grid: &Grid,
    events: LegEvents,
    sensor: &SensorModel,
    rng: &mut ChaCha8Rng,
) -> Result<SimLeg> {
    let kin = kinematics::evaluate(leg, sh, &timeline.heading, grid, timeline.n_idx());
    let strides = strides::stride_truth(
        leg,
        &events,
        &kin.fine,
        &timeline.heading,
        timeline.ramp_end_s,
        timeline.slowdown_start_s,
    );
    let m = measure(
        sensor,
        &kin.dense.acc_clean_g,
        &kin.dense.gyro_clean_dps,
        rng,
    );
    let sat_count = m.saturated.iter().filter(|&&s| s).count();
    let recording = Recording::new(grid.fs_hz, m.acc_g, m.gyro_dps, m.saturated)?
        .with_sensor_saturation(m.acc_saturated, m.gyro_saturated)?
        .with_side(leg.side);
    let mounting = &leg.mounting;
    let truth = LegTruth {
        side: leg.side,
        sensor_height_m: leg.p.sensor_height_m,
        sensor: SensorTruth {
            axial_misalignment_deg: mounting.axial_deg,
            tilt_misalignment_deg: mounting.tilt_deg,
            mirrored: mounting.mirrored,
            device_axes_in_f: mounting.mount,
            gyro_bias_dps: if sensor.noise {
                m.gyro_bias_dps
            } else {
                [0.0; 3]
            },
            acc_bias_g: if sensor.noise { m.acc_bias_g } else { [0.0; 3] },
            saturated_samples: sat_count,
        },
        hs_times_s: events.hs,
        to_times_s: events.to,
        strides,
        pitch_deg: kin.pitch_deg,
        roll_deg: kin.roll_deg,
        yaw_deg: kin.yaw_deg,
    };
    Ok(SimLeg {
        recording,
        truth,
        dense: kin.dense,
    })
}

//! `SpaceDemo`'s pose task: the hand's full pose as the task (the page's
//! "Hand" choice, the address's `task=pose`), the target's orientation by
//! roll, pitch and yaw (the number fields), by a rotation matrix (the 3-D
//! view's rotation gizmo) or turned about a world axis (the keys), and
//! `Z`'s orientation weight.

use wasm_bindgen::prelude::*;

use super::super::{js_err, JsResult};
use super::SpaceDemo;

#[wasm_bindgen]
impl SpaceDemo {
    /// `position` (the hand's position, the default) or `pose` (its full
    /// pose, the target's orientation the hand's at the start). Throws,
    /// changing nothing, on another name, for a chain of fewer than six
    /// joints or a method that does not run the pose (Cases 1 and 3).
    #[wasm_bindgen(js_name = setTask)]
    pub fn set_task(&mut self, task: &str) -> JsResult {
        let on = match task {
            "position" => false,
            "pose" => true,
            other => {
                return Err(JsError::new(&format!(
                    "task '{other}': expected position or pose"
                )))
            }
        };
        self.session_mut().set_pose_task(on).map_err(js_err)
    }

    /// The target's orientation by roll, pitch and yaw (rad; URDF's fixed
    /// axes, as `--target X,Y,Z,ROLL,PITCH,YAW`). Throws, changing
    /// nothing, for the position task, a non-finite angle or a path other
    /// than the line.
    #[wasm_bindgen(js_name = setTargetOrientation)]
    pub fn set_target_orientation(&mut self, roll: f64, pitch: f64, yaw: f64) -> JsResult {
        self.session_mut()
            .set_target_rpy([roll, pitch, yaw])
            .map_err(js_err)
    }

    /// The target's orientation as a rotation matrix, nine numbers by rows
    /// (the rotation gizmo's). Throws as `setTargetOrientation` does, or
    /// for another count.
    #[wasm_bindgen(js_name = setTargetRotation)]
    pub fn set_target_rotation(&mut self, rows: Vec<f64>) -> JsResult {
        let r: [f64; 9] = rows.as_slice().try_into().map_err(|_| {
            JsError::new(&format!(
                "a rotation needs 9 numbers by rows, got {}",
                rows.len()
            ))
        })?;
        let m = [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]];
        self.session_mut().set_target_rotation(&m).map_err(js_err)
    }

    /// Turns the target's orientation by `angle` (rad) about world axis
    /// `axis` (0: x, 1: y, 2: z): the rotation keys.
    #[wasm_bindgen(js_name = turnTarget)]
    pub fn turn_target(&mut self, axis: usize, angle: f64) -> JsResult {
        self.session_mut().turn_target(axis, angle).map_err(js_err)
    }

    /// `Z`'s orientation weight `z` (m²/rad²) of the pose task.
    #[wasm_bindgen(js_name = setOrientationWeight)]
    pub fn set_orientation_weight(&mut self, weight: f64) -> JsResult {
        self.session_mut()
            .set_orientation_weight(weight)
            .map_err(js_err)
    }
}

// Camera moves of arcus_view, pure geometry on arcus_camera and on the camera of an
// arcus_rainbow_sky (no GL, no library calls), so the window's input handlers can apply
// them while a frame renders.
#pragma once

#include "arcus/arcus.h"

namespace arcus_view {

// Rotates the position about look_at (radians): yaw about the camera's up, positive
// counter-clockwise seen from above (the camera moves right); pitch about its right
// axis, positive raising the camera.  A pitch that would bring the view
// direction within 1° of up or down is dropped, since the camera frame degenerates there.
void orbit(arcus_camera& camera, double yaw, double pitch);

// Turns the view in place: look_at rotates about the position (positive yaw: to the
// left, counter-clockwise seen from above; positive pitch: up), with orbit's limit.
void turn(arcus_camera& camera, double yaw, double pitch);

// Moves position and look_at together by `forward` along the view direction and
// `right` to the side, each a fraction of the distance to look_at, so the orbit
// radius and with it the step size stay the same.
void move(arcus_camera& camera, double forward, double right);

// Rainbow skies: the camera stays where it is and looks about.  Turns camera_forward by
// `right` about the world's up (0, 1, 0) and by `up` about the camera's right axis
// (radians; positive: to the right, up), holding the view's elevation within ±89°, and
// sets camera_up to the world's up (a level horizon).
void look(arcus_rainbow_sky& sky, double right, double up);

// Multiplies the field of view by `factor`, held within 5°-150°.
void zoom(arcus_rainbow_sky& sky, double factor);

}  // namespace arcus_view

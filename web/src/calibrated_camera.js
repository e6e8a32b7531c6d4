// A three.js camera that is exactly a calibrated camera of the `cameras` message: its
// projection is the server's GL projection of K (render/camera_projection.hpp: NDC y = +1 at
// the image's top row, w = z_cam) and its view is T_cam_base (OpenCV camera frame: x right,
// y down, z forward), both used verbatim. three.js otherwise recomputes a camera's matrices
// from a position, an orientation and a field of view, which cannot express a principal
// point off centre, skew or OpenCV's pixel-centre convention.

import * as THREE from 'three';

export class CalibratedCamera extends THREE.Camera {
  // projection, view: 16 numbers each, column-major (THREE.Matrix4.fromArray's order).
  constructor(projection, view) {
    super();
    this.matrixAutoUpdate = false;
    // WebGLRenderer.render() would otherwise recompute matrixWorldInverse as the inverse of
    // matrixWorld: the view would pick up the round-off of two inversions.
    this.matrixWorldAutoUpdate = false;
    this.set(projection, view);
  }

  set(projection, view) {
    this.projectionMatrix.fromArray(projection);
    this.projectionMatrixInverse.copy(this.projectionMatrix).invert();
    this.matrixWorldInverse.fromArray(view);
    this.matrixWorld.copy(this.matrixWorldInverse).invert();
    this.matrix.copy(this.matrixWorld);
    this.matrix.decompose(this.position, this.quaternion, this.scale);
  }

  updateMatrixWorld() {}
  updateWorldMatrix() {}
}

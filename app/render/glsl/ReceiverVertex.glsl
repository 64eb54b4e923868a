// Vertex stage of an eclipse receiver (EclipseShading). Inserted in place of the camera
// declarations tag of VTK's poly-data vertex shader, so it declares the two camera
// matrices itself: MCVCMatrix is then always present (VTK only declares it for lit
// actors) and VTK sets both. (No VTK tag may appear in these files, comments included:
// VTK substitutes them anywhere.)
//
// A receiver's model coordinates are centred on the body with the world's axes (the
// actor only translates by centre - origin), so vertexMC is the position relative to
// the body's centre: small numbers, full float precision at any distance.
uniform mat4 MCDCMatrix;
uniform mat4 MCVCMatrix;
uniform mat3 umbraInertialToBodyFixed;  // the receiver's body-fixed frame (its albedo map's)

out vec3 umbraPosMC;              // rasterised facet point, body-centred (m)
flat out vec3 umbraEyeMC;         // camera position, body-centred (perspective)
flat out vec3 umbraViewDirMC;     // direction of projection (parallel)
flat out int umbraParallel;       // 1 for a parallel projection
flat out vec3 umbraEyeLon;        // cos, sin and angle of the eye's body-fixed longitude (the map lookup)

void umbraReceiverVertex(vec4 posMC) {
  umbraPosMC = posMC.xyz;
  mat4 vcmc = inverse(MCVCMatrix);
  umbraEyeMC = (vcmc * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
  umbraViewDirMC = normalize((vcmc * vec4(0.0, 0.0, -1.0, 0.0)).xyz);
  // The projection's w row is (0, 0, -1, 0) for a perspective, (0, 0, 0, 1) for a
  // parallel projection.
  mat4 vcdc = MCDCMatrix * vcmc;
  umbraParallel = abs(vcdc[2][3]) < 0.5 ? 1 : 0;
  vec3 eyeB = umbraInertialToBodyFixed * (umbraParallel == 1 ? -umbraViewDirMC : umbraEyeMC);
  float h = length(eyeB.xy);
  umbraEyeLon = h > 0.0 ? vec3(eyeB.xy / h, atan(eyeB.y, eyeB.x)) : vec3(1.0, 0.0, 0.0);
}

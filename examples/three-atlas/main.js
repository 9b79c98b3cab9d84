// The atlas files (atlas.ktx2, atlas.glsl) from `tilekit texture atlas`, beside this page or at
// ?atlas=PATH/atlas (no extension); ?filter=hardware uses the texture unit's anisotropic filter.
import * as THREE from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';

const query = new URLSearchParams(location.search);
const stem = query.get('atlas') || 'atlas';
const hardware = query.get('filter') === 'hardware';

const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setSize(innerWidth, innerHeight);
document.body.appendChild(renderer.domElement);
const camera = new THREE.PerspectiveCamera(60, innerWidth / innerHeight, 0.05, 200);
camera.position.set(0, 1.5, 6);
camera.lookAt(0, 0, -10);

const [atlas, glsl] = await Promise.all([
  new KTX2Loader().detectSupport(renderer).loadAsync(stem + '.ktx2'),  // RGBA8: no transcoder needed
  fetch(stem + '.glsl').then(r => r.text()),
]);
atlas.wrapS = atlas.wrapT = THREE.RepeatWrapping;  // the atlas is a toroidal tiling: no gutters
atlas.minFilter = THREE.LinearMipmapLinearFilter;
atlas.magFilter = THREE.LinearFilter;
atlas.anisotropy = hardware ? renderer.capabilities.getMaxAnisotropy() : 1;

// A ground plane 400 tiles a side; uv in tiles of the infinite virtual texture.
const material = new THREE.ShaderMaterial({
  glslVersion: THREE.GLSL3,
  uniforms: { tk_atlas: { value: atlas } },
  vertexShader: `
    out vec2 tk_uv;
    void main() {
      tk_uv = uv * 400.0;
      gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
    }`,
  fragmentShader: `${glsl}
    in vec2 tk_uv;
    out vec4 tk_colour;
    void main() {
      vec2 dx = dFdx(tk_uv), dy = dFdy(tk_uv);
      // the sRGB atlas is sampled in linear light; three's output colour space encodes it again
      tk_colour = linearToOutputTexel(${hardware ? 'tk_texture_grad' : 'tk_texture'}(tk_uv, dx, dy));
    }`,
});
const ground = new THREE.Mesh(new THREE.PlaneGeometry(100, 100), material);
ground.rotation.x = -Math.PI / 2;
const scene = new THREE.Scene();
scene.add(ground);

addEventListener('resize', () => {
  camera.aspect = innerWidth / innerHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(innerWidth, innerHeight);
});
renderer.setAnimationLoop(t => {
  camera.position.z = 6 - t * 0.0005;  // walk forward slowly
  renderer.render(scene, camera);
});
window.tkReady = true;

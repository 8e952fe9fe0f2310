// A copy of proto/channels.json, the channel table of the frame format (web/test/codec.test.mjs
// checks it byte for byte): edit the JSON, then copy it between the two marker lines.
export const TABLE =
{
  "about": "Floe's frame channels: each defined once here. The server, the Rust codec (floe-proto's build.rs generates its table from this file), gRPC, REST, the WebSocket and the viewer's JavaScript decoder (web/js/codec/channels.js, checked equal to this file by web/test/codec.test.mjs) all use these names, tags and units. Tags are fixed forever; a new channel takes the next free tag below 64. Tags 64 to 255 are assigned per scene to channels a module declares without a row here; a scene's info lists them with their names and units.",
  "dynamic_tags": [64, 255],
  "channels": [
    { "name": "position", "tag": 0, "components": 3, "unit": "m", "exact": false, "bits": 16,
      "about": "Particle position; always the first channel of a particle frame, quantised over the scene bounds." },
    { "name": "velocity", "tag": 1, "components": 3, "unit": "m/s", "exact": false, "bits": 10,
      "about": "Particle velocity." },
    { "name": "density", "tag": 2, "components": 1, "unit": "kg/m^3", "exact": false, "bits": 10,
      "about": "SPH density." },
    { "name": "pressure", "tag": 3, "components": 1, "unit": "Pa", "exact": false, "bits": 10,
      "about": "Pressure." },
    { "name": "temperature", "tag": 4, "components": 1, "unit": "K", "exact": false, "bits": 10,
      "about": "Temperature." },
    { "name": "material", "tag": 5, "components": 1, "unit": "", "exact": true, "bits": 8,
      "about": "Index of the particle's material in the scene's material table, sent exactly (0 to 255)." },
    { "name": "grid", "tag": 6, "components": 3, "unit": "m", "exact": false, "bits": 16,
      "about": "Grid frames only, always their first channel: the grid's extent per axis (range min = origin, max = origin + size) and its cell counts (payload: three u32)." },
    { "name": "ids", "tag": 7, "components": 1, "unit": "", "exact": false, "bits": 16,
      "about": "Identity-ordered frames of a set whose particles are born and die (version 5), always their last channel: the live particles' stable ids, ascending, in the frame's particle order (range min = first id, max = last id; payload: the gaps predictor's stream)." }
  ]
}
;

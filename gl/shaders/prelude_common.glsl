// The part of the GLSL environment every technique and atomic mode shares
// (the module assembly has defined ha_word, ha_word_bits and ha_payload_bits,
// and the HA_BINDING_* points, which hosts choose through GlBindings): the
// parameters of core/shared/ha_params.h as one uniform block (a host shader
// needs no uniforms of ours, only our buffers bound), and the GLSL spellings
// of what the shared sources expect from their host.
#define HA_PARAMS_BEGIN layout(std140, binding = HA_BINDING_PARAMS) uniform HaParams {
#define HA_PARAMS_END };
#define HA_PARAM_UINT(name) uint name;
#define HA_PARAM_FLOAT(name) float name;
#define HA_PARAM_UVEC2(name) uvec2 name;

// The data a kit pass's hooks read beside LinePoint: the pass's optional input buffer
// `hook_buffer` as a flat uint array (std430), on the pin's binding (HOOK_BUFFER_BINDING, by
// declaration). Include it from a hook file; the kit refuses a program that reads it when the
// pass has nothing connected to `hook_buffer` (lines::program looks for the block HookBuffer).
#ifndef PATHLET_LINE_HOOK_BUFFER_GLSL
#define PATHLET_LINE_HOOK_BUFFER_GLSL

layout(std430, binding = HOOK_BUFFER_BINDING) readonly buffer HookBuffer { uint hook_buffer[]; };

#endif

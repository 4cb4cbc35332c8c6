// Paged lists' environment on the GPU (techniques/paged_lists/cpu/
// include/habuffer/techniques/paged_lists/paged_lists.glsl), after the linked lists' lists_env.glsl
// (head image, node entries and links; the module assembly makes them
// coherent, HABUFFER_LISTS_QUALIFIER, since an insertion reads heads other
// invocations swap) and before paged_lists.glsl. The node counter is the
// lists' word of the counters buffer (zeroed before every gather), advanced
// by a page at a time; the pages allocated and never linked are counted in
// the word after the fixed arrays' (HABUFFER_COUNTER_NODES + 2), which only
// a debugger reads. Node entries and links are written after the head's
// swap and read only by the sort pass, after a barrier.
#define HABUFFER_COUNTER_WASTED_PAGES (HABUFFER_COUNTER_NODES + 2u)
uint pl_load_head(uint pixel) { return ha_heads[pixel]; }
uint pl_swap_head(uint pixel, uint expected, uint link) { return atomicCompSwap(ha_heads[pixel], expected, link); }
uint pl_allocate_page() { return atomicAdd(ha_counters[HABUFFER_COUNTER_NODES], HABUFFER_PAGE_NODES); }
void pl_waste_page() { atomicAdd(ha_counters[HABUFFER_COUNTER_WASTED_PAGES], 1u); }

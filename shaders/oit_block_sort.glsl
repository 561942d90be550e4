// The block sort of a pixel's fragment list (Knowles, Leach, Zambetta, "Fast Sorting for Exact
// OIT of Complex Scenes", 2014): a list of any length sorted in rounds of a bounded local array.
// Each round walks the list and keeps, by insertion, the OIT_BLOCK nearest fragments that come
// after the last one of the round before, in the lists' order made total by the node index.
// Registers: OIT_BLOCK entries, whatever the list's length; a round that keeps fewer was the last.
// resolve_exact sorts every fragment so; resolve_list the nearest max_fragments (one insertion
// sort of 32 was 1.6x slower on an H200 and 2x on llvmpipe than rounds of 16).
// Needs oit_list.glsl, OIT_BLOCK and the pass's u_nodes (the nodes as a buffer texture).
#ifndef PATHLET_OIT_BLOCK_SORT_GLSL
#define PATHLET_OIT_BLOCK_SORT_GLSL

// (d, id, c, n) comes before (d2, id2, c2, n2): oit_nearer, made total by the node index.
bool oit_before(float d, uint id, uint c, uint n, float d2, uint id2, uint c2, uint n2) {
    return oit_nearer(d, id, c, d2, id2, c2) || (d == d2 && id == id2 && c == c2 && n < n2);
}

// A round's block, nearest first: depth, line id, colour and node index of each fragment.
float oit_block_dep[OIT_BLOCK];
uint oit_block_lid[OIT_BLOCK], oit_block_col[OIT_BLOCK], oit_block_idx[OIT_BLOCK];

// The fragment after which the next round starts (the block's last); none before the first.
struct OitBlockAfter {
    bool any;
    float d;
    uint id, c, n;
};
const OitBlockAfter kOitBlockStart = OitBlockAfter(false, 0.0, 0u, 0u, 0u);
OitBlockAfter oit_block_last() {
    return OitBlockAfter(true, oit_block_dep[OIT_BLOCK - 1], oit_block_lid[OIT_BLOCK - 1],
                         oit_block_col[OIT_BLOCK - 1], oit_block_idx[OIT_BLOCK - 1]);
}

// One round over the list at `head`: fills the block with the nearest fragments after `after`
// and returns how many (< OIT_BLOCK: the list's last round). `walked`: the nodes walked; more
// than max_walk only a corrupt (cyclic) list has: the walk stops there and `cut` says so. `cut`
// also says when the walk ended before the list did for any other reason: drivers end long
// loops as if their condition were false (llvmpipe after 65535 iterations), which the node left
// in hand shows.
int oit_sort_block(uint head, OitBlockAfter after, uint max_walk, out uint walked, out bool cut) {
    int n = 0;
    walked = 0u;
    cut = false;
    // Only the first n entries are read; setting the last keeps the compiler from warning.
    oit_block_dep[OIT_BLOCK - 1] = 1.0, oit_block_lid[OIT_BLOCK - 1] = 0u;
    oit_block_col[OIT_BLOCK - 1] = 0u, oit_block_idx[OIT_BLOCK - 1] = 0u;
    uint i = head;
    for (; i != OIT_END;) {
        if (++walked > max_walk) break;
        uvec4 node = texelFetch(u_nodes, int(i));
        uint self = i;
        i = oit_next(node);
        float d = oit_depth(node);
        uint id = oit_line(node), c = node.x;
        if (after.any && !oit_before(after.d, after.id, after.c, after.n, d, id, c, self)) continue;  // an earlier round's
        if (n == OIT_BLOCK && !oit_before(d, id, c, self, oit_block_dep[OIT_BLOCK - 1], oit_block_lid[OIT_BLOCK - 1],
                                          oit_block_col[OIT_BLOCK - 1], oit_block_idx[OIT_BLOCK - 1]))
            continue;  // beyond this round's block
        int j = n < OIT_BLOCK ? n++ : OIT_BLOCK - 1;
        for (; j > 0 && oit_before(d, id, c, self, oit_block_dep[j - 1], oit_block_lid[j - 1], oit_block_col[j - 1],
                                   oit_block_idx[j - 1]); --j) {
            oit_block_dep[j] = oit_block_dep[j - 1];
            oit_block_lid[j] = oit_block_lid[j - 1];
            oit_block_col[j] = oit_block_col[j - 1];
            oit_block_idx[j] = oit_block_idx[j - 1];
        }
        oit_block_dep[j] = d;
        oit_block_lid[j] = id;
        oit_block_col[j] = c;
        oit_block_idx[j] = self;
    }
    cut = i != OIT_END;  // stopped at max_walk, or by the driver
    return n;
}

#endif

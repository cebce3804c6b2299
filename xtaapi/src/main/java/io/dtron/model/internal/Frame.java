package io.dtron.model.internal;

/** Allocates the frame slots of one function, edge or invariant. */
final class Frame {
    private int next;
    private int max;

    Frame(int start) {
        this.next = start;
        this.max = start;
    }

    int allocate(int slots) {
        int slot = next;
        next += Math.max(1, slots);
        max = Math.max(max, next);
        return slot;
    }

    int mark() {
        return next;
    }

    void release(int mark) {
        next = mark;
    }

    int size() {
        return max;
    }
}

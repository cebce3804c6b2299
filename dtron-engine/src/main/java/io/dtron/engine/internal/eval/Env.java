package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;
import io.dtron.model.Function;
import io.dtron.model.Network;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Pos;
import java.util.Arrays;

/**
 * The state of one evaluation: the integer state vector, the stack of frames, the clock resets collected.
 *
 * <p>Integer data is reached through one address space: addresses {@code 0..varCount-1} are slots of the state
 * vector {@link #vars}, addresses from {@code varCount} on are slots of {@link #stack} (address {@code varCount +
 * k} is {@code stack[k]}). The bottom of the stack holds constant tables that are indexed at run time; above
 * them come the frames: the caller's frame of the top-level expression (a copy), then one frame per function
 * call. {@link #bp} is the stack index of the current frame's slot 0. A reference parameter's slot holds such an
 * address (or a clock or channel number, for references to clocks and channels), so a reference into a
 * caller's frame stays valid while the callee runs, even when the stack grows.
 */
final class Env {
    /** The largest number of loop iterations and calls in one evaluation. */
    static final int MAX_STEPS = 10_000_000;
    /** The deepest nesting of function calls. */
    static final int MAX_DEPTH = 1000;

    static final int NORMAL = 0;
    static final int BREAK = 1;
    static final int CONTINUE = 2;
    static final int RETURN = 3;

    final Network network;
    final int varCount;
    int[] vars;
    int[] stack = new int[256];
    /** The number of stack slots taken by constant tables. */
    int pool;
    /** The stack index of the current frame. */
    int bp;
    /** The first free stack index. */
    int sp;
    ClockResets resets;
    int steps;
    int depth;
    /** The function called last, for the message when the Java stack runs out. */
    Function callee;
    /** The value of the last {@code return} of an integer. */
    int ret;
    /** Where {@code return} copies an array or struct to. */
    int retAddr;

    Env(Network network) {
        this.network = network;
        this.varCount = network.stateSize();
    }

    /** Starts a top-level evaluation with a copy of {@code frame} (may be null) in a frame of {@code slots}. */
    void begin(int[] vars, int[] frame, int slots, ClockResets resets) {
        if (vars.length != varCount) {
            throw new IllegalArgumentException("the state vector has " + vars.length + " slots, not " + varCount);
        }
        this.vars = vars;
        this.resets = resets;
        steps = 0;
        depth = 0;
        callee = null;
        sp = pool;
        int n = frame == null ? 0 : frame.length;
        bp = reserve(Math.max(n, slots));
        if (n > 0) {
            System.arraycopy(frame, 0, stack, bp, n);
        }
    }

    int load(int address) {
        return address < varCount ? vars[address] : stack[address - varCount];
    }

    void store(int address, int value) {
        if (address < varCount) {
            vars[address] = value;
        } else {
            stack[address - varCount] = value;
        }
    }

    /** Copies {@code length} slots; both ranges lie wholly in the state vector or wholly in the stack. */
    void copy(int from, int to, int length) {
        int[] src = from < varCount ? vars : stack;
        int[] dst = to < varCount ? vars : stack;
        System.arraycopy(src, from < varCount ? from : from - varCount, dst, to < varCount ? to : to - varCount,
                length);
    }

    /** Takes {@code n} stack slots; returns the stack index of the first. */
    int reserve(int n) {
        int base = sp;
        sp += n;
        if (sp > stack.length) {
            stack = Arrays.copyOf(stack, Math.max(sp, stack.length * 2));
        }
        return base;
    }

    /** Puts constant values at the bottom of the stack (only between evaluations); returns their address. */
    int addConstants(int[] values) {
        int base = pool;
        sp = pool;
        reserve(values.length);
        System.arraycopy(values, 0, stack, base, values.length);
        pool += values.length;
        sp = pool;
        return varCount + base;
    }

    /** Counts a loop iteration or call. */
    void tick(Pos pos) {
        if (++steps > MAX_STEPS) {
            throw new ModelRuntimeException(pos, "the evaluation went on for more than " + MAX_STEPS
                    + " loop iterations and function calls; is there an endless loop?");
        }
    }

    /** The error for calls nested too deeply, by {@link #MAX_DEPTH} or by the Java stack's size. */
    ModelRuntimeException tooDeep() {
        String in = callee == null ? "" : " (in '" + callee.name() + "')";
        return new ModelRuntimeException(callee == null ? null : callee.pos(), "the calls nest " + depth
                + " deep" + in + ", too deep to go on; is there an endless recursion?");
    }

    /** The name of what {@code target} denotes at {@code address}, e.g. {@code Gate.list[3]} or {@code p.a}. */
    String describe(int address, Expression target) {
        if (address >= 0 && address < varCount) {
            for (Variable v : network.variables()) {
                if (address >= v.offset() && address < v.offset() + v.size()) {
                    return v.name() + path(v.type(), address - v.offset());
                }
            }
        }
        return target.pos().text();
    }

    private static String path(Type type, int relative) {
        StringBuilder sb = new StringBuilder();
        Type t = type;
        int rest = relative;
        while (true) {
            if (t instanceof Type.Array a) {
                int size = a.element().slots();
                int i = rest / size;
                rest -= i * size;
                sb.append('[').append(a.firstIndex() + i).append(']');
                t = a.element();
            } else if (t instanceof Type.Struct s) {
                int k = s.fields().size() - 1;
                while (s.offsetOf(k) > rest) {
                    k--;
                }
                rest -= s.offsetOf(k);
                sb.append('.').append(s.fields().get(k).name());
                t = s.fields().get(k).type();
            } else {
                return sb.toString();
            }
        }
    }
}

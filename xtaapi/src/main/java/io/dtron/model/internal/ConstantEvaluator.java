package io.dtron.model.internal;

import io.dtron.model.Expression;
import io.dtron.model.Function;
import io.dtron.model.Statement;
import io.dtron.model.Type;
import java.util.Arrays;

/**
 * Evaluates at compile time an expression that calls functions on constants, as Uppaal does for
 * {@code const int P = def_prio(13);}: the functions run on their own frames and may read constants and
 * their parameters only. Anything else (a variable, a clock, a reference parameter, an error at run time such
 * as an overflow or a failed assert, more than a million steps) makes the expression not computable.
 */
final class ConstantEvaluator {
    private static final int MAX_STEPS = 1_000_000;
    private static final int MAX_DEPTH = 1_000;

    private final Compilation compilation;
    private int steps;
    private int depth;
    private int[] returned;

    private ConstantEvaluator(Compilation compilation) {
        this.compilation = compilation;
    }

    /** Thrown when the expression cannot be computed at compile time. */
    private static final class NotConstant extends RuntimeException {
        private static final long serialVersionUID = 1L;

        NotConstant() {
            super(null, null, false, false);
        }
    }

    /** How a statement ended. */
    private enum Flow { NORMAL, BREAK, CONTINUE, RETURN }

    /** A slot of a frame or a constant table. */
    private record Place(int[] store, int offset) {
    }

    /** The flat values of {@code x}, or null when it calls no function or cannot be computed at compile time. */
    static int[] evaluate(Expression x, Compilation compilation) {
        if (!callsFunction(x)) {
            return null;
        }
        try {
            return new ConstantEvaluator(compilation).values(x, new int[0]);
        } catch (NotConstant e) {
            return null;
        }
    }

    private static boolean callsFunction(Expression e) {
        if (e instanceof Expression.Call) {
            return true;
        } else if (e instanceof Expression.Unary u) {
            return callsFunction(u.operand());
        } else if (e instanceof Expression.Binary b) {
            return callsFunction(b.left()) || callsFunction(b.right());
        } else if (e instanceof Expression.Conditional c) {
            return callsFunction(c.condition()) || callsFunction(c.then()) || callsFunction(c.otherwise());
        } else if (e instanceof Expression.Index i) {
            return callsFunction(i.array()) || callsFunction(i.index());
        } else if (e instanceof Expression.FieldRef f) {
            return callsFunction(f.struct());
        }
        return false;
    }

    private int[] values(Expression x, int[] frame) {
        Type t = x.type();
        if (t.isIntegral() && t.slots() == 1) {
            return new int[] {value(x, frame)};
        }
        if (x instanceof Expression.Call c) {
            return call(c, frame);
        }
        if (!(t instanceof Type.Array || t instanceof Type.Struct)) {
            throw new NotConstant();
        }
        Place p = place(x, frame);
        return Arrays.copyOfRange(p.store(), p.offset(), p.offset() + t.slots());
    }

    private int value(Expression x, int[] frame) {
        if (x instanceof Expression.Constant c) {
            return c.value();
        } else if (x instanceof Expression.LocalRef || x instanceof Expression.Index
                || x instanceof Expression.FieldRef) {
            Place p = place(x, frame);
            return p.store()[p.offset()];
        } else if (x instanceof Expression.Unary u) {
            int v = value(u.operand(), frame);
            if (u.op() == Expression.Operator.NEG) {
                return checked(-(long) v);
            }
            return v == 0 ? 1 : 0;
        } else if (x instanceof Expression.Binary b) {
            return binary(b, frame);
        } else if (x instanceof Expression.Conditional c) {
            return value(c.condition(), frame) != 0 ? value(c.then(), frame) : value(c.otherwise(), frame);
        } else if (x instanceof Expression.Assign a) {
            Place p = place(a.target(), frame);
            int v = value(a.value(), frame);
            if (a.op() != null) {
                v = arithmetic(a.op(), p.store()[p.offset()], v);
            }
            return store(p, a.target().type(), v);
        } else if (x instanceof Expression.Increment i) {
            Place p = place(i.target(), frame);
            int old = p.store()[p.offset()];
            int v = store(p, i.target().type(), checked((long) old + i.delta()));
            return i.prefix() ? v : old;
        } else if (x instanceof Expression.Call c) {
            return call(c, frame)[0];
        } else if (x instanceof Expression.Quantified q) {
            long result = q.quantifier() == Expression.Quantifier.FORALL ? 1 : 0;
            for (int i = q.lower(); i <= q.upper(); i++) {
                step();
                frame[q.slot()] = i;
                int v = value(q.body(), frame);
                switch (q.quantifier()) {
                    case FORALL -> result = result != 0 && v != 0 ? 1 : 0;
                    case EXISTS -> result = result != 0 || v != 0 ? 1 : 0;
                    case SUM -> result = checked(result + v);
                }
            }
            return (int) result;
        }
        throw new NotConstant();
    }

    private static int store(Place p, Type type, int v) {
        if (type instanceof Type.Int i && (v < i.lower() || v > i.upper())) {
            throw new NotConstant();
        }
        int stored = type instanceof Type.Bool ? (v != 0 ? 1 : 0) : v;
        p.store()[p.offset()] = stored;
        return stored;
    }

    private int binary(Expression.Binary b, int[] frame) {
        int l = value(b.left(), frame);
        switch (b.op()) {
            case AND -> {
                return l != 0 && value(b.right(), frame) != 0 ? 1 : 0;
            }
            case OR -> {
                return l != 0 || value(b.right(), frame) != 0 ? 1 : 0;
            }
            case IMPLY -> {
                return l == 0 || value(b.right(), frame) != 0 ? 1 : 0;
            }
            default -> {
                // both operands below
            }
        }
        int r = value(b.right(), frame);
        return switch (b.op()) {
            case LT -> l < r ? 1 : 0;
            case LE -> l <= r ? 1 : 0;
            case EQ -> l == r ? 1 : 0;
            case NE -> l != r ? 1 : 0;
            case GE -> l >= r ? 1 : 0;
            case GT -> l > r ? 1 : 0;
            default -> arithmetic(b.op(), l, r);
        };
    }

    private static int arithmetic(Expression.Operator op, int x, int y) {
        return switch (op) {
            case ADD -> checked((long) x + y);
            case SUB -> checked((long) x - y);
            case MUL -> checked((long) x * y);
            case DIV, MOD -> {
                if (y == 0) {
                    throw new NotConstant();
                }
                yield checked(op == Expression.Operator.DIV ? (long) x / y : (long) x % y);
            }
            case POW -> {
                if (y < 0) {
                    throw new NotConstant();
                }
                yield checked(Checker.power(x, y));
            }
            case SHL -> checked((long) x << y);
            case SHR -> x >> y;
            case MIN -> Math.min(x, y);
            case MAX -> Math.max(x, y);
            case BIT_AND -> x & y;
            case BIT_OR -> x | y;
            case BIT_XOR -> x ^ y;
            default -> throw new NotConstant();
        };
    }

    private static int checked(long v) {
        if (v < Integer.MIN_VALUE || v > Integer.MAX_VALUE) {
            throw new NotConstant();
        }
        return (int) v;
    }

    private Place place(Expression x, int[] frame) {
        if (x instanceof Expression.LocalRef l && !l.reference()) {
            return new Place(frame, l.slot());
        } else if (x instanceof Expression.ConstantTable t) {
            return new Place(t.values(), 0);
        } else if (x instanceof Expression.Call c) {
            return new Place(call(c, frame), 0);
        } else if (x instanceof Expression.Index i && i.array().type() instanceof Type.Array a) {
            Place base = place(i.array(), frame);
            int index = value(i.index(), frame);
            if (index < a.firstIndex() || index >= a.firstIndex() + a.length()) {
                throw new NotConstant();
            }
            return new Place(base.store(), base.offset() + (index - a.firstIndex()) * a.element().slots());
        } else if (x instanceof Expression.FieldRef f && f.struct().type() instanceof Type.Struct s) {
            Place base = place(f.struct(), frame);
            return new Place(base.store(), base.offset() + s.offsetOf(f.field()));
        }
        throw new NotConstant();
    }

    private int[] call(Expression.Call c, int[] frame) {
        Function f = compilation.compiledFunction(c.function());
        if (f == null || depth >= MAX_DEPTH) {
            throw new NotConstant();
        }
        int[] callee = new int[Math.max(1, f.frameSize())];
        for (int i = 0; i < f.parameters().size(); i++) {
            Function.Parameter p = f.parameters().get(i);
            if (p.reference()) {
                throw new NotConstant();
            }
            int[] v = values(c.args().get(i), frame);
            System.arraycopy(v, 0, callee, p.slot(), v.length);
        }
        depth++;
        try {
            returned = null;
            exec(f.body(), callee);
            if (returned == null) {
                throw new NotConstant();
            }
            int[] result = returned;
            returned = null;
            return result;
        } finally {
            depth--;
        }
    }

    private void step() {
        if (++steps > MAX_STEPS) {
            throw new NotConstant();
        }
    }

    private Flow exec(Statement s, int[] frame) {
        step();
        if (s instanceof Statement.Block b) {
            for (Statement st : b.statements()) {
                Flow flow = exec(st, frame);
                if (flow != Flow.NORMAL) {
                    return flow;
                }
            }
            return Flow.NORMAL;
        } else if (s instanceof Statement.Eval e) {
            evaluateForEffect(e.expression(), frame);
            return Flow.NORMAL;
        } else if (s instanceof Statement.InitLocal l) {
            int[] v = l.initial() == null ? DeclarationCompiler.defaults(l.type()) : values(l.initial(), frame);
            System.arraycopy(v, 0, frame, l.slot(), v.length);
            return Flow.NORMAL;
        } else if (s instanceof Statement.If i) {
            if (value(i.condition(), frame) != 0) {
                return exec(i.then(), frame);
            }
            return i.otherwise() == null ? Flow.NORMAL : exec(i.otherwise(), frame);
        } else if (s instanceof Statement.While w) {
            while (value(w.condition(), frame) != 0) {
                Flow flow = exec(w.body(), frame);
                if (flow == Flow.BREAK) {
                    break;
                }
                if (flow == Flow.RETURN) {
                    return flow;
                }
            }
            return Flow.NORMAL;
        } else if (s instanceof Statement.DoWhile d) {
            do {
                Flow flow = exec(d.body(), frame);
                if (flow == Flow.BREAK) {
                    break;
                }
                if (flow == Flow.RETURN) {
                    return flow;
                }
            } while (value(d.condition(), frame) != 0);
            return Flow.NORMAL;
        } else if (s instanceof Statement.For f) {
            f.init().forEach(e -> evaluateForEffect(e, frame));
            while (f.condition() == null || value(f.condition(), frame) != 0) {
                Flow flow = exec(f.body(), frame);
                if (flow == Flow.BREAK) {
                    break;
                }
                if (flow == Flow.RETURN) {
                    return flow;
                }
                f.step().forEach(e -> evaluateForEffect(e, frame));
            }
            return Flow.NORMAL;
        } else if (s instanceof Statement.Iterate it) {
            for (int i = it.lower(); i <= it.upper(); i++) {
                frame[it.slot()] = i;
                Flow flow = exec(it.body(), frame);
                if (flow == Flow.BREAK) {
                    break;
                }
                if (flow == Flow.RETURN) {
                    return flow;
                }
            }
            return Flow.NORMAL;
        } else if (s instanceof Statement.Return r) {
            returned = r.value() == null ? new int[0] : values(r.value(), frame);
            return Flow.RETURN;
        } else if (s instanceof Statement.Break) {
            return Flow.BREAK;
        } else if (s instanceof Statement.Continue) {
            return Flow.CONTINUE;
        } else if (s instanceof Statement.Assert a) {
            if (value(a.condition(), frame) == 0) {
                throw new NotConstant();
            }
            return Flow.NORMAL;
        }
        throw new NotConstant();
    }

    private void evaluateForEffect(Expression e, int[] frame) {
        if (e instanceof Expression.Assign a && !(a.target().type().isIntegral() && a.target().type().slots() == 1)) {
            Place p = place(a.target(), frame);
            int[] v = values(a.value(), frame);
            System.arraycopy(v, 0, p.store(), p.offset(), v.length);
        } else if (e.type().isIntegral() && e.type().slots() == 1) {
            value(e, frame);
        } else {
            values(e, frame);
        }
    }
}

package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;
import io.dtron.model.Expression.Operator;
import io.dtron.model.Function;
import io.dtron.model.Network;
import io.dtron.model.Statement;
import io.dtron.model.Type;
import java.util.ArrayList;
import java.util.IdentityHashMap;
import java.util.List;
import java.util.Map;

/**
 * Turns the network's expressions and function bodies into node trees, once each. Functions are compiled on
 * their first call site; constant tables that are indexed at run time are placed in the stack's constant pool.
 * While a top-level expression is compiled it records how many frame slots (selects, quantified names) it uses.
 */
final class Compiler {
    private final Network network;
    private final Env env;
    private final FunctionCode[] functions;
    private final Map<Expression.ConstantTable, Integer> tables = new IdentityHashMap<>();
    private boolean inFunction;
    /** The functions whose code exists and whose bodies are still to compile ({@link #function}). */
    private final java.util.ArrayDeque<Integer> bodiesToCompile = new java.util.ArrayDeque<>();
    /** Whether a call of {@link #function} further out compiles the bodies of {@link #bodiesToCompile}. */
    private boolean compilingBodies;
    private int rootSlots;

    Compiler(Network network, Env env) {
        this.network = network;
        this.env = env;
        this.functions = new FunctionCode[network.functions().size()];
    }

    /** Starts compiling a top-level expression. */
    void beginRoot() {
        rootSlots = 0;
        inFunction = false;
    }

    /** The frame slots the top-level expression compiled since {@link #beginRoot} needs. */
    int rootSlots() {
        return rootSlots;
    }

    private void useSlots(int slot, int count) {
        if (!inFunction) {
            rootSlots = Math.max(rootSlots, slot + Math.max(1, count));
        }
    }

    static boolean isAggregate(Type t) {
        return (t instanceof Type.Array || t instanceof Type.Struct) && t.clocks() == 0 && t.channels() == 0;
    }

    // ================================================================ values

    ValueNode value(Expression e) {
        if (e instanceof Expression.Constant c) {
            return new ValueNode.Const(c.value());
        } else if (e instanceof Expression.Assign a) {
            return assign(a);
        } else if (e instanceof Expression.Increment i) {
            return new Updates.Increment(place(i.target()), Range.of(i.target().type()), i);
        } else if (e instanceof Expression.Call c && !isAggregate(c.type())) {
            FunctionCode code = function(c.function());
            return new FunctionCode.Call(code, args(code.function, c), c.pos());
        } else if (e instanceof Expression.ModelError m) {
            return new ValueNode.Fail(m);
        } else if (isAggregate(e.type())) {
            return new ValueNode.Discard(copy(e), e.type().slots());
        } else if (e.type() instanceof Type.ClockConstraint) {
            throw new IllegalArgumentException("'" + e.pos().text() + "' constrains clocks: use constrain()");
        } else if (!e.type().isIntegral()) {
            throw new IllegalArgumentException("'" + e.pos().text() + "' is not a data expression");
        } else if (e instanceof Expression.VariableRef v) {
            return new ValueNode.VarRead(v.variable().offset());
        } else if (e instanceof Expression.LocalRef l && !l.reference()) {
            useSlots(l.slot(), 1);
            return new ValueNode.LocalRead(l.slot());
        } else if (e instanceof Expression.LocalRef || e instanceof Expression.Index
                || e instanceof Expression.FieldRef) {
            PlaceNode p = place(e);
            if (p instanceof PlaceNode.Fixed f && f.address < env.varCount) {
                return new ValueNode.VarRead(f.address);
            }
            return readsResult(e) ? new ValueNode.ResultRead(p) : new ValueNode.PlaceRead(p);
        } else if (e instanceof Expression.Unary u) {
            ValueNode operand = value(u.operand());
            return u.op() == Operator.NEG ? new ValueNode.Neg(operand, u) : new ValueNode.Not(operand);
        } else if (e instanceof Expression.Binary b) {
            return binary(b, value(b.left()), value(b.right()));
        } else if (e instanceof Expression.Conditional c) {
            return new ValueNode.Conditional(value(c.condition()), value(c.then()), value(c.otherwise()));
        } else if (e instanceof Expression.Quantified q) {
            useSlots(q.slot(), 1);
            ValueNode body = value(q.body());
            return switch (q.quantifier()) {
                case FORALL -> new ValueNode.Forall(q, body);
                case EXISTS -> new ValueNode.Exists(q, body);
                case SUM -> new ValueNode.Sum(q, body);
            };
        }
        throw new IllegalArgumentException("'" + e.pos().text() + "' is not a data expression");
    }

    private static ValueNode binary(Expression.Binary b, ValueNode l, ValueNode r) {
        return switch (b.op()) {
            case ADD -> new ValueNode.Add(l, r, b);
            case SUB -> new ValueNode.Sub(l, r, b);
            case POW -> new ValueNode.Pow(l, r, b);
            case MUL -> new ValueNode.Mul(l, r, b);
            case DIV -> new ValueNode.Div(l, r, b);
            case MOD -> new ValueNode.Mod(l, r, b);
            case SHL -> new ValueNode.Shl(l, r, b);
            case SHR -> new ValueNode.Shr(l, r);
            case MIN -> new ValueNode.Min(l, r);
            case MAX -> new ValueNode.Max(l, r);
            case BIT_AND -> new ValueNode.BitAnd(l, r);
            case BIT_OR -> new ValueNode.BitOr(l, r);
            case BIT_XOR -> new ValueNode.BitXor(l, r);
            case LT -> new ValueNode.Lt(l, r);
            case LE -> new ValueNode.Le(l, r);
            case EQ -> new ValueNode.Eq(l, r);
            case NE -> new ValueNode.Ne(l, r);
            case GE -> new ValueNode.Ge(l, r);
            case GT -> new ValueNode.Gt(l, r);
            case AND -> new ValueNode.And(l, r);
            case OR -> new ValueNode.Or(l, r);
            case IMPLY -> new ValueNode.Imply(l, r);
            case NEG, NOT -> throw new IllegalArgumentException("not a binary operator: " + b.op());
        };
    }

    private ValueNode assign(Expression.Assign a) {
        Type t = a.target().type();
        PlaceNode target = place(a.target());
        if (t instanceof Type.Clock) {
            return new Updates.ClockAssign(target, value(a.value()), a);
        }
        if (isAggregate(t)) {
            return new Updates.AssignAll(target, copy(a.value()));
        }
        Range range = Range.of(t);
        ValueNode value = value(a.value());
        return a.op() == null ? new Updates.Assign(target, value, range, a)
                : new Updates.Compound(target, value, range, a);
    }

    // ================================================================ places

    /** The address of integer data, or the number of a clock or channel. */
    PlaceNode place(Expression e) {
        if (e instanceof Expression.VariableRef v) {
            return new PlaceNode.Fixed(v.variable().offset());
        } else if (e instanceof Expression.ClockRef c) {
            return new PlaceNode.Fixed(c.clock().index());
        } else if (e instanceof Expression.ChannelRef c) {
            return new PlaceNode.Fixed(c.channel().index());
        } else if (e instanceof Expression.LocalRef l) {
            useSlots(l.slot(), l.reference() ? 1 : l.type().slots());
            return l.reference() ? new PlaceNode.Ref(l.slot()) : new PlaceNode.Local(l.slot());
        } else if (e instanceof Expression.ConstantTable t) {
            return new PlaceNode.Fixed(tables.computeIfAbsent(t, k -> env.addConstants(k.values())));
        } else if (e instanceof Expression.Index ix) {
            Type.Array a = (Type.Array) ix.array().type();
            PlaceNode array = place(ix.array());
            int size = a.clocks() > 0 ? a.element().clocks()
                    : a.channels() > 0 ? a.element().channels() : a.element().slots();
            if (ix.index() instanceof Expression.Constant c && c.value() >= a.firstIndex()
                    && c.value() < a.firstIndex() + a.length()) {
                return offset(array, (c.value() - a.firstIndex()) * size);
            }
            return new PlaceNode.Index(array, value(ix.index()), a.firstIndex(), a.length(), size, ix);
        } else if (e instanceof Expression.FieldRef f) {
            Type.Struct s = (Type.Struct) f.struct().type();
            return offset(place(f.struct()), s.offsetOf(f.field()));
        } else if (e instanceof Expression.Call c && isAggregate(c.type())) {
            return new PlaceNode.Result(copy(c), c.type().slots());
        } else if (e instanceof Expression.ModelError m) {
            return new PlaceNode.Fail(m);
        }
        throw new ModelRuntimeException(e.pos(), "'" + e.pos().text() + "' is not supported here: only variables,"
                + " parameters, function results and their elements and fields can be indexed or selected");
    }

    /** Whether an element or field is one of a function's result. */
    private static boolean readsResult(Expression e) {
        Expression root = e;
        while (root instanceof Expression.Index || root instanceof Expression.FieldRef) {
            root = root instanceof Expression.Index i ? i.array() : ((Expression.FieldRef) root).struct();
        }
        return root instanceof Expression.Call;
    }

    private static PlaceNode offset(PlaceNode base, int offset) {
        if (offset == 0) {
            return base;
        }
        if (base instanceof PlaceNode.Fixed f) {
            return new PlaceNode.Fixed(f.address + offset);
        }
        return new PlaceNode.Offset(base, offset);
    }

    // ================================================================ arrays and structs

    /** An array or struct value. */
    CopyNode copy(Expression e) {
        if (e instanceof Expression.Call c) {
            FunctionCode code = function(c.function());
            return new FunctionCode.CallCopy(code, args(code.function, c), c.pos());
        } else if (e instanceof Expression.Assign a) {
            return new Updates.AssignAllValue((Updates.AssignAll) assign(a), a.type().slots());
        } else if (e instanceof Expression.ModelError m) {
            return new CopyNode.Fail(m);
        }
        return new CopyNode.FromPlace(place(e), e.type().slots());
    }

    // ================================================================ functions

    private FunctionCode.Arg[] args(Function f, Expression.Call call) {
        FunctionCode.Arg[] args = new FunctionCode.Arg[call.args().size()];
        for (int k = 0; k < args.length; k++) {
            Function.Parameter p = f.parameters().get(k);
            Expression arg = call.args().get(k);
            if (p.reference()) {
                args[k] = new FunctionCode.RefArg(p.slot(), place(arg));
            } else if (isAggregate(p.type())) {
                args[k] = new FunctionCode.CopyArg(p.slot(), copy(arg));
            } else {
                args[k] = new FunctionCode.ValueArg(p.slot(), value(arg), Range.of(p.type()), p.name(), arg.pos());
            }
        }
        return args;
    }

    /**
     * The code of function {@code index}. Its body is compiled after the call that asks for it, from a list, not
     * inside it: a chain of functions each calling the next (a thousand deep) would otherwise compile as deep a
     * recursion and overflow the stack.
     */
    private FunctionCode function(int index) {
        FunctionCode code = functions[index];
        if (code != null) {
            return code;
        }
        code = new FunctionCode(network.functions().get(index));
        functions[index] = code;
        bodiesToCompile.add(index);
        if (compilingBodies) {
            return code; // the outermost call compiles it
        }
        compilingBodies = true;
        boolean outer = inFunction;
        boolean done = false;
        try {
            inFunction = true;
            while (!bodiesToCompile.isEmpty()) {
                int next = bodiesToCompile.peek();
                Function f = network.functions().get(next);
                functions[next].body = statement(f.body(), f);
                bodiesToCompile.poll();
            }
            done = true;
        } finally {
            inFunction = outer;
            compilingBodies = false;
            if (!done) {
                // a body that does not compile: neither it nor those still to compile are kept
                for (int pending : bodiesToCompile) {
                    functions[pending] = null;
                }
                bodiesToCompile.clear();
            }
        }
        return code;
    }

    private StatementNode statement(Statement s, Function f) {
        if (s instanceof Statement.Block b) {
            StatementNode[] nodes = new StatementNode[b.statements().size()];
            for (int k = 0; k < nodes.length; k++) {
                nodes[k] = statement(b.statements().get(k), f);
            }
            return new StatementNode.Block(nodes);
        } else if (s instanceof Statement.Eval e) {
            return new StatementNode.Eval(value(e.expression()));
        } else if (s instanceof Statement.InitLocal l) {
            return initLocal(l);
        } else if (s instanceof Statement.If i) {
            return new StatementNode.If(value(i.condition()), statement(i.then(), f),
                    i.otherwise() == null ? null : statement(i.otherwise(), f));
        } else if (s instanceof Statement.While w) {
            return new StatementNode.While(value(w.condition()), statement(w.body(), f), w.pos());
        } else if (s instanceof Statement.DoWhile d) {
            return new StatementNode.DoWhile(statement(d.body(), f), value(d.condition()), d.pos());
        } else if (s instanceof Statement.For l) {
            return new StatementNode.For(values(l.init()), l.condition() == null ? null : value(l.condition()),
                    values(l.step()), statement(l.body(), f), l.pos());
        } else if (s instanceof Statement.Iterate it) {
            return new StatementNode.Iterate(it.slot(), it.lower(), it.upper(), statement(it.body(), f), it.pos());
        } else if (s instanceof Statement.Return r) {
            if (r.value() == null) {
                return new StatementNode.ReturnVoid();
            }
            if (isAggregate(f.returnType())) {
                return new StatementNode.ReturnCopy(copy(r.value()));
            }
            return new StatementNode.ReturnValue(value(r.value()), Range.of(f.returnType()), f.name(), r.value());
        } else if (s instanceof Statement.Break) {
            return new StatementNode.Break();
        } else if (s instanceof Statement.Continue) {
            return new StatementNode.Continue();
        }
        Statement.Assert a = (Statement.Assert) s;
        return new StatementNode.Assert(value(a.condition()), a.condition());
    }

    private StatementNode initLocal(Statement.InitLocal l) {
        if (isAggregate(l.type())) {
            CopyNode value = l.initial() != null ? copy(l.initial())
                    : new CopyNode.FromPlace(new PlaceNode.Fixed(env.addConstants(defaults(l.type()))),
                            l.type().slots());
            return new StatementNode.InitCopy(l.slot(), value);
        }
        Range range = Range.of(l.type());
        ValueNode value = l.initial() != null ? value(l.initial()) : new ValueNode.Const(range.defaultValue());
        return new StatementNode.InitValue(l.slot(), value, range, l.pos());
    }

    /** The default values of an array or struct: 0, or the bound nearest to 0 of a range without 0. */
    private static int[] defaults(Type type) {
        List<Integer> values = new ArrayList<>();
        addDefaults(type, values);
        return values.stream().mapToInt(Integer::intValue).toArray();
    }

    private static void addDefaults(Type type, List<Integer> out) {
        if (type instanceof Type.Array a) {
            for (int k = 0; k < a.length(); k++) {
                addDefaults(a.element(), out);
            }
        } else if (type instanceof Type.Struct s) {
            for (Type.Field field : s.fields()) {
                addDefaults(field.type(), out);
            }
        } else {
            out.add(Range.of(type).defaultValue());
        }
    }

    private ValueNode[] values(List<Expression> exprs) {
        ValueNode[] nodes = new ValueNode[exprs.size()];
        for (int k = 0; k < nodes.length; k++) {
            nodes[k] = value(exprs.get(k));
        }
        return nodes;
    }

    // ================================================================ guards and invariants

    Conjunction conjunction(Expression e) {
        List<ValueNode> data = new ArrayList<>();
        List<Conjunction.Atom> atoms = new ArrayList<>();
        List<Conjunction.Alternative> alternatives = new ArrayList<>();
        Expression[] unsupported = new Expression[1];
        conjuncts(e, data, atoms, alternatives, unsupported);
        return new Conjunction(data.toArray(new ValueNode[0]), atoms.toArray(new Conjunction.Atom[0]),
                alternatives.toArray(new Conjunction.Alternative[0]), unsupported[0]);
    }

    private void conjuncts(Expression e, List<ValueNode> data, List<Conjunction.Atom> atoms,
                           List<Conjunction.Alternative> alternatives, Expression[] unsupported) {
        if (!(e.type() instanceof Type.ClockConstraint)) {
            data.add(value(e));
        } else if (e instanceof Expression.Binary b && b.op() == Operator.AND) {
            conjuncts(b.left(), data, atoms, alternatives, unsupported);
            conjuncts(b.right(), data, atoms, alternatives, unsupported);
        } else if (e instanceof Expression.Binary b && b.op() == Operator.OR
                && b.left().type() instanceof Type.ClockConstraint != b.right().type() instanceof Type.ClockConstraint) {
            boolean leftIsData = !(b.left().type() instanceof Type.ClockConstraint);
            alternatives.add(new Conjunction.Alternative(value(leftIsData ? b.left() : b.right()),
                    conjunction(leftIsData ? b.right() : b.left())));
        } else if (e instanceof Expression.Binary b && isBound(b.op())) {
            atoms.add(atom(b));
        } else if (unsupported[0] == null) {
            unsupported[0] = e;
        }
    }

    private static boolean isBound(Operator op) {
        return op == Operator.LT || op == Operator.LE || op == Operator.EQ || op == Operator.GE
                || op == Operator.GT;
    }

    private Conjunction.Atom atom(Expression.Binary b) {
        Expression l = b.left();
        Expression r = b.right();
        Operator op = b.op();
        if (!isClockTerm(l) || isClockTerm(r) && !isClockTerm(l)) {
            Expression t = l;
            l = r;
            r = t;
            op = flip(op);
        }
        if (isClockTerm(r)) {
            // x ~ y (or with offsets): x - y ~ 0
            Term left = term(l);
            Term right = term(r);
            Term diff = new Term(left.i, right.i, minus(b.pos(), left.offset, right.offset));
            return new Conjunction.Atom(place(diff.i), place(diff.j), op, value(negate(b.pos(), diff.offset)), b.pos());
        }
        Term t = term(l);
        Expression bound = t.offset == null ? r : minus(b.pos(), r, t.offset);
        return new Conjunction.Atom(place(t.i), t.j == null ? null : place(t.j), op, value(bound), b.pos());
    }

    /** A clock term {@code x_i - x_j + offset}; {@code j} and {@code offset} may be null. */
    private record Term(Expression i, Expression j, Expression offset) {
    }

    /** Splits a clock, a clock plus or minus an integer, or a clock difference (with offsets) into a term. */
    private Term term(Expression e) {
        if (e instanceof Expression.Binary b && (b.op() == Operator.ADD || b.op() == Operator.SUB)) {
            boolean lc = isClockTerm(b.left());
            boolean rc = isClockTerm(b.right());
            if (lc && rc) {
                Term left = term(b.left());
                Term right = term(b.right());
                return new Term(left.i, right.i, minus(b.pos(), left.offset, right.offset));
            }
            if (lc) {
                Term left = term(b.left());
                Expression k = b.op() == Operator.ADD ? b.right() : negate(b.pos(), b.right());
                return new Term(left.i, left.j, plus(b.pos(), left.offset, k));
            }
            Term right = term(b.right());
            if (b.op() == Operator.ADD) {
                return new Term(right.i, right.j, plus(b.pos(), b.left(), right.offset));
            }
            // k - (x - y + o) = (y - x) + (k - o)
            return new Term(right.j, right.i, minus(b.pos(), b.left(), right.offset));
        }
        return new Term(e, null, null);
    }

    private static Expression plus(io.dtron.xta.Pos pos, Expression a, Expression b) {
        if (a == null) {
            return b;
        }
        return b == null ? a : new Expression.Binary(pos, Type.Int.UNBOUNDED, Operator.ADD, a, b);
    }

    private static Expression minus(io.dtron.xta.Pos pos, Expression a, Expression b) {
        if (b == null) {
            return a;
        }
        return a == null ? negate(pos, b) : new Expression.Binary(pos, Type.Int.UNBOUNDED, Operator.SUB, a, b);
    }

    private static Expression negate(io.dtron.xta.Pos pos, Expression a) {
        return a == null ? new Expression.Constant(pos, Type.Int.UNBOUNDED, 0)
                : new Expression.Unary(pos, Type.Int.UNBOUNDED, Operator.NEG, a);
    }

    private static boolean isClockTerm(Expression e) {
        return e.type() instanceof Type.Clock || e.type() instanceof Type.ClockDifference;
    }

    private static Operator flip(Operator op) {
        return switch (op) {
            case LT -> Operator.GT;
            case LE -> Operator.GE;
            case GT -> Operator.LT;
            case GE -> Operator.LE;
            default -> op;
        };
    }
}

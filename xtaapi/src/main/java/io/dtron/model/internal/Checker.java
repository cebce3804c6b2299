package io.dtron.model.internal;

import io.dtron.model.Expression;
import io.dtron.model.Expression.Operator;
import io.dtron.model.Function;
import io.dtron.model.Type;
import io.dtron.model.Type.ConstraintKind;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.ArrayDim;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.TypeExpr;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * Resolves names, checks types and folds constants: turns AST expressions and types into the network's
 * {@link Expression}s and {@link Type}s. Returns null after reporting an error, so that one mistake gives
 * one message.
 */
final class Checker {
    private final Compilation compilation;
    private final Diagnostics diagnostics;
    private Scope scope;
    private final Frame frame;
    /** Set when an expression used a free parameter that is not declared const. */
    boolean usedNonConstFreeParam;
    /** Set when an expression used a placeholder of a template checked without instantiation. */
    boolean usedPlaceholder;
    /** Set when an expression used a reference parameter (never computable at compile time, as in Uppaal). */
    boolean usedReference;

    Checker(Compilation compilation, Scope scope, Frame frame) {
        this.compilation = compilation;
        this.diagnostics = compilation.diagnostics;
        this.scope = scope;
        this.frame = frame;
    }

    Scope scope() {
        return scope;
    }

    Frame frame() {
        return frame;
    }

    void enter(Scope inner) {
        scope = inner;
    }

    void leave(Scope outer) {
        scope = outer;
    }

    private <T> T error(Pos pos, String message) {
        diagnostics.error(pos, message);
        return null;
    }

    // ================================================================ types

    /** A resolved type with its qualifiers. */
    record Resolved(Type type, boolean constant, boolean meta) {
    }

    Resolved resolve(TypeExpr t) {
        boolean constant = t.qualifiers().contains(TypeExpr.Qualifier.CONST);
        boolean meta = t.qualifiers().contains(TypeExpr.Qualifier.META);
        boolean urgent = t.qualifiers().contains(TypeExpr.Qualifier.URGENT);
        boolean broadcast = t.qualifiers().contains(TypeExpr.Qualifier.BROADCAST);
        Type base;
        if (t instanceof TypeExpr.IntType i) {
            if (i.lower() == null) {
                base = Type.Int.DEFAULT;
            } else {
                Integer lo = requireConstant(i.lower(), "the lower bound of an integer range");
                Integer hi = requireConstant(i.upper(), "the upper bound of an integer range");
                if (lo == null || hi == null) {
                    return null;
                }
                if (lo > hi) {
                    return error(t.pos(), "the integer range [" + lo + "," + hi + "] is empty");
                }
                base = new Type.Int(lo, hi);
            }
        } else if (t instanceof TypeExpr.PrimitiveType p) {
            base = switch (p.primitive()) {
                case BOOL -> Type.Bool.INSTANCE;
                case CLOCK -> Type.Clock.INSTANCE;
                case CHAN -> new Type.Channel(urgent, broadcast);
                case VOID -> Type.Void.INSTANCE;
                case DOUBLE -> Type.Double.INSTANCE;
            };
            if (base instanceof Type.Double) {
                unsupportedDouble(t.pos());
            }
        } else if (t instanceof TypeExpr.ScalarType s) {
            Integer size = requireConstant(s.size(), "the size of a scalar set");
            if (size == null) {
                return null;
            }
            if (size < 1) {
                return error(s.size().pos(), "a scalar set needs at least one value, not " + size);
            }
            base = new Type.Scalar(size, compilation.nextScalarId(), "scalar[" + size + "]");
        } else if (t instanceof TypeExpr.StructType s) {
            List<Type.Field> fields = new ArrayList<>();
            for (TypeExpr.Field f : s.fields()) {
                Resolved r = resolve(f.type());
                if (r == null) {
                    return null;
                }
                Type ft = applyDims(r.type(), f.dims());
                if (ft == null) {
                    return null;
                }
                if (ft.clocks() > 0 || ft.channels() > 0 || containsClockOrChannel(ft)) {
                    return error(f.pos(), "field '" + f.name() + "': structs of clocks or channels are not supported");
                }
                if (fields.stream().anyMatch(x -> x.name().equals(f.name()))) {
                    return error(f.pos(), "field '" + f.name() + "' is declared twice");
                }
                fields.add(new Type.Field(f.name(), ft));
            }
            base = new Type.Struct(fields);
        } else {
            TypeExpr.NamedType n = (TypeExpr.NamedType) t;
            Symbol sym = scope.lookup(n.name());
            if (!(sym instanceof Symbol.TypeName tn)) {
                if (sym == null && !compilation.firstUnknown("type", n.name())) {
                    return null;
                }
                return error(t.pos(), sym == null ? "unknown type '" + n.name() + "'"
                        : "'" + n.name() + "' is not a type");
            }
            base = tn.type();
            constant |= tn.constant();
            if ((urgent || broadcast) && base instanceof Type.Channel c) {
                base = new Type.Channel(c.urgent() || urgent, c.broadcast() || broadcast);
            }
        }
        if ((urgent || broadcast) && !(base instanceof Type.Channel)) {
            return error(t.pos(), (urgent ? "'urgent'" : "'broadcast'") + " applies to channels only, not to " + base);
        }
        if (t.qualifiers().contains(TypeExpr.Qualifier.HYBRID)) {
            if (!(base instanceof Type.Clock)) {
                return error(t.pos(), "'hybrid' applies to clocks only, not to " + base);
            }
            compilation.unsupported(t.pos(), "a hybrid clock", "hybrid clocks belong to statistical model checking,"
                    + " and the engine treats clocks symbolically, as zones");
        }
        return new Resolved(base, constant, meta);
    }

    private void unsupportedDouble(Pos pos) {
        compilation.unsupported(pos, "real numbers (double)", "the engine computes with integers and clock zones");
    }

    private static boolean containsClockOrChannel(Type t) {
        if (t instanceof Type.Clock || t instanceof Type.Channel) {
            return true;
        }
        if (t instanceof Type.Array a) {
            return containsClockOrChannel(a.element());
        }
        return false;
    }

    /** {@code base} with array dimensions; {@code int a[2][3]} is an array of 2 arrays of 3. */
    Type applyDims(Type base, List<ArrayDim> dims) {
        Type t = base;
        for (int i = dims.size() - 1; i >= 0; i--) {
            Type index = dimIndex(dims.get(i));
            if (index == null) {
                return null;
            }
            t = new Type.Array(t, index);
        }
        return t;
    }

    private Type dimIndex(ArrayDim dim) {
        TypeExpr typeExpr = dim.type();
        if (typeExpr == null && dim.size() instanceof Expr.Ident id && scope.lookup(id.name()) instanceof Symbol.TypeName) {
            typeExpr = new TypeExpr.NamedType(id.pos(), java.util.Set.of(), id.name());
        }
        if (typeExpr != null) {
            Resolved r = resolve(typeExpr);
            if (r == null) {
                return null;
            }
            if (r.type() instanceof Type.Int i && !i.equals(Type.Int.DEFAULT) || r.type() instanceof Type.Scalar) {
                return r.type();
            }
            return error(dim.pos(), "an array can be indexed by a bounded integer range or a scalar set, not by "
                    + r.type());
        }
        Integer size = requireConstant(dim.size(), "an array size");
        if (size == null) {
            return null;
        }
        if (size < 1) {
            return error(dim.size().pos(), "an array needs at least one element, not " + size);
        }
        return new Type.Int(0, size - 1);
    }

    // ================================================================ constants

    /** The value of an integer expression that must be known at compile time, or null after an error. */
    Integer requireConstant(Expr e, String what) {
        Expression x = compile(e);
        if (x == null) {
            return null;
        }
        if (x instanceof Expression.ModelError m) {
            return error(e.pos(), m.message());
        }
        int[] values = constantValues(x);
        if (values == null || values.length != 1 || !x.type().isIntegral()) {
            if (x.type() instanceof Type.Double) {
                return error(e.pos(), what + " must be an integer, not a double");
            }
            return error(e.pos(), what + " must be computable at compile time");
        }
        if (x.type() instanceof Type.Scalar) {
            return error(e.pos(), what + " must be an integer");
        }
        return values[0];
    }

    /**
     * The flat values of {@code x} when it is computable at compile time: a constant, or calls of functions
     * without side effects on constants, evaluated as Uppaal does; null otherwise.
     */
    int[] constantValues(Expression x) {
        int[] values = constantValuesOf(x);
        return values != null ? values : ConstantEvaluator.evaluate(x, compilation);
    }

    /** The flat values of a constant expression of any type, or null if it is not a folded constant. */
    private static int[] constantValuesOf(Expression x) {
        if (x instanceof Expression.Constant c) {
            return new int[] {c.value()};
        }
        if (x instanceof Expression.ConstantTable t) {
            return t.values();
        }
        return null;
    }

    // ================================================================ expressions

    Expression compile(Expr e) {
        if (e instanceof Expr.IntLit i) {
            if (i.value() > Integer.MAX_VALUE) {
                return error(e.pos(), "the number " + i.value() + " does not fit in 32 bits");
            }
            return new Expression.Constant(e.pos(), Type.Int.UNBOUNDED, (int) i.value());
        } else if (e instanceof Expr.BoolLit b) {
            return new Expression.Constant(e.pos(), Type.Bool.INSTANCE, b.value() ? 1 : 0);
        } else if (e instanceof Expr.StringLit s) {
            return new Expression.StringConstant(e.pos(), Type.Str.INSTANCE, s.value());
        } else if (e instanceof Expr.DoubleLit d) {
            unsupportedDouble(e.pos());
            return new Expression.DoubleConstant(e.pos(), Type.Double.INSTANCE, d.value());
        } else if (e instanceof Expr.Spawn s) {
            return spawn(s);
        } else if (e instanceof Expr.Deadlock) {
            return error(e.pos(), "'deadlock' can only be used in queries");
        } else if (e instanceof Expr.Ident id) {
            return ident(id);
        } else if (e instanceof Expr.Index ix) {
            return index(ix);
        } else if (e instanceof Expr.Field f) {
            return field(f);
        } else if (e instanceof Expr.Call c) {
            return call(c);
        } else if (e instanceof Expr.Unary u) {
            return unary(u);
        } else if (e instanceof Expr.Binary b) {
            return binary(b);
        } else if (e instanceof Expr.Conditional c) {
            return conditional(c);
        } else if (e instanceof Expr.Assign a) {
            return assign(a);
        } else {
            return quantifier((Expr.Quantifier) e);
        }
    }

    private Expression ident(Expr.Ident id) {
        Symbol sym = scope.lookup(id.name());
        Pos pos = id.pos();
        if (sym == null) {
            return compilation.firstUnknown("name", id.name()) ? error(pos, "unknown name '" + id.name() + "'") : null;
        }
        if (sym instanceof Symbol.Constant c) {
            return c.type().slots() == 1 && c.type().isIntegral()
                    ? new Expression.Constant(pos, c.type(), c.values()[0])
                    : new Expression.ConstantTable(pos, c.type(), c.values());
        } else if (sym instanceof Symbol.Var v) {
            return new Expression.VariableRef(pos, v.variable().type(), v.variable());
        } else if (sym instanceof Symbol.ClockVar c) {
            return new Expression.ClockRef(pos, c.clock().type(), c.clock());
        } else if (sym instanceof Symbol.ChanVar c) {
            return new Expression.ChannelRef(pos, c.channel().type(), c.channel());
        } else if (sym instanceof Symbol.Local l) {
            return new Expression.LocalRef(pos, l.type(), l.slot(), id.name(), l.reference());
        } else if (sym instanceof Symbol.FreeParam f) {
            if (!f.declaredConst()) {
                usedNonConstFreeParam = true;
            }
            return new Expression.Constant(pos, f.type(), f.value());
        } else if (sym instanceof Symbol.Alias a) {
            if (a.target() instanceof Expression.DoubleConstant d) {
                // a double constant, also one of Uppaal's built-in ones (M_PI), stands where it is used
                unsupportedDouble(pos);
                return new Expression.DoubleConstant(pos, d.type(), d.value());
            }
            if (a.placeholder()) {
                usedPlaceholder = true;
            }
            if (a.reference()) {
                usedReference = true;
            }
            return a.target();
        } else if (sym instanceof Symbol.TypeName) {
            return error(pos, "'" + id.name() + "' is a type, not a value");
        } else if (sym instanceof Symbol.Func) {
            return error(pos, "'" + id.name() + "' is a function: call it as " + id.name() + "(...)");
        } else if (sym instanceof Symbol.Template) {
            return error(pos, "'" + id.name() + "' is a template, not a value");
        } else {
            return error(pos, "'" + id.name() + "' is a process, not a value");
        }
    }

    private Expression index(Expr.Index ix) {
        Expression array = compile(ix.array());
        Expression index = compile(ix.index());
        if (array == null || index == null) {
            return null;
        }
        if (!(array.type() instanceof Type.Array a)) {
            return error(ix.array().pos(), "'" + ix.array().pos().text() + "' is not an array (it is "
                    + describe(array.type()) + ")");
        }
        if (a.index() instanceof Type.Scalar s) {
            if (!(index.type() instanceof Type.Scalar is) || is.id() != s.id()) {
                return error(ix.index().pos(), "this array is indexed by the scalar set " + s
                        + "; the index must be of that set, not " + describe(index.type()));
            }
        } else if (!isInteger(index.type())) {
            return error(ix.index().pos(), "an array index must be an integer, not " + describe(index.type()));
        }
        Type element = a.element();
        if (index instanceof Expression.Constant c) {
            int first = a.firstIndex();
            int last = first + a.length() - 1;
            if (c.value() < first || c.value() > last) {
                String message = "index " + c.value() + " is out of range [" + first + "," + last + "] of '"
                        + ix.array().pos().text() + "'";
                diagnostics.warning(ix.pos(), message + "; evaluating it is a model error");
                if (!(array instanceof Expression.ConstantTable)) {
                    // as in Uppaal, an error when the run evaluates it; it is still a variable that can be assigned
                    return new Expression.Index(ix.pos(), element, array, index);
                }
                return new Expression.ModelError(ix.pos(), element, message);
            }
            if (array instanceof Expression.ConstantTable t) {
                int offset = (c.value() - first) * element.slots();
                return slice(ix.pos(), element, t, offset);
            }
        }
        if (array instanceof Expression.ModelError m) {
            return new Expression.ModelError(ix.pos(), element, m.message());
        }
        return new Expression.Index(ix.pos(), element, array, index);
    }

    private static Expression slice(Pos pos, Type type, Expression.ConstantTable t, int offset) {
        if (type.slots() == 1 && type.isIntegral()) {
            return new Expression.Constant(pos, type, t.value(offset));
        }
        return new Expression.ConstantTable(pos, type, Arrays.copyOfRange(t.values(), offset, offset + type.slots()));
    }

    private Expression field(Expr.Field f) {
        Expression value = compile(f.value());
        if (value == null) {
            return null;
        }
        if (!(value.type() instanceof Type.Struct s)) {
            return error(f.pos(), "'" + f.value().pos().text() + "' is not a struct, so it has no field '"
                    + f.name() + "'");
        }
        int i = s.fieldIndex(f.name());
        if (i < 0) {
            return error(f.pos(), "the struct has no field '" + f.name() + "'");
        }
        Type type = s.fields().get(i).type();
        if (value instanceof Expression.ConstantTable t) {
            return slice(f.pos(), type, t, s.offsetOf(i));
        }
        return new Expression.FieldRef(f.pos(), type, value, i);
    }

    private Expression call(Expr.Call c) {
        if (!(c.function() instanceof Expr.Ident id)) {
            return error(c.function().pos(), "only functions can be called");
        }
        Symbol sym = scope.lookup(id.name());
        if (sym instanceof Symbol.External x) {
            return external(c, x);
        }
        if (sym == null && ("exit".equals(id.name()) || "numOf".equals(id.name()))) {
            return dynamicBuiltin(c, id.name());
        }
        if (sym == null && Builtins.of(id.name()) != null) {
            return builtin(c, id.name(), Builtins.of(id.name()));
        }
        if (!(sym instanceof Symbol.Func f)) {
            if (sym == null && !compilation.firstUnknown("function", id.name())) {
                return null;
            }
            return error(id.pos(), sym == null ? "unknown function '" + id.name() + "'"
                    : "'" + id.name() + "' is not a function");
        }
        FunctionInfo info = f.info();
        if (c.args().size() != info.parameters.size()) {
            return error(c.pos(), "'" + id.name() + "' takes " + info.parameters.size() + " argument"
                    + (info.parameters.size() == 1 ? "" : "s") + ", not " + c.args().size());
        }
        List<Expression> args = new ArrayList<>();
        boolean ok = true;
        for (int i = 0; i < c.args().size(); i++) {
            Function.Parameter p = info.parameters.get(i);
            Expr argExpr = c.args().get(i);
            Expression arg = compile(argExpr);
            if (arg == null) {
                ok = false;
                continue;
            }
            if (p.reference()) {
                String why = notAssignable(argExpr);
                if (!isLvalue(arg) || why != null && !(p.type() instanceof Type.Channel)) {
                    error(argExpr.pos(), "argument " + (i + 1) + " of '" + id.name() + "' is passed by reference, so it"
                            + " must be a variable" + (why == null ? "" : " (" + why + ")"));
                    ok = false;
                } else if (!sameReferenceType(p.type(), arg.type())) {
                    error(argExpr.pos(), "argument " + (i + 1) + " of '" + id.name() + "' must be " + p.type()
                            + " (a reference parameter takes exactly its type), not " + describe(arg.type()));
                    ok = false;
                }
            } else if (!assignable(p.type(), arg)) {
                error(argExpr.pos(), "argument " + (i + 1) + " of '" + id.name() + "' must be " + p.type() + ", not "
                        + describe(arg.type()));
                ok = false;
            } else if (isClockValue(arg.type())) {
                unsupportedClockArithmetic(argExpr.pos());
            }
            args.add(arg);
        }
        return ok ? new Expression.Call(c.pos(), info.returnType, info.index, info.name, args) : null;
    }

    /** A call of a built-in function of statistical model checking (see {@link Builtins}). */
    private Expression builtin(Expr.Call c, String name, Builtins.Signature signature) {
        List<Expression> args = arguments(c, name, signature.parameters(), null);
        if (args == null) {
            return null;
        }
        compilation.unsupported(c.pos(), "built-in", "the built-in function '" + name + "'", "the engine evaluates the"
                + " integer functions of the model, not the real-valued and random functions of statistical model"
                + " checking");
        return new Expression.Builtin(c.pos(), signature.returns(), name, args);
    }

    /** A call of an external function of an {@code import} block. */
    private Expression external(Expr.Call c, Symbol.External x) {
        List<Expression> args = arguments(c, x.name(), x.parameters(), x.references());
        if (args == null) {
            return null;
        }
        compilation.unsupported(c.pos(), "external", "the external function '" + x.name() + "' of \"" + x.library()
                + "\"",
                "the engine does not load native libraries");
        return new Expression.Builtin(c.pos(), x.returnType(), x.name(), args);
    }

    /**
     * The checked arguments of a call of {@code name} with parameters of types {@code types} ({@code references}
     * says which are references; null for none), or null after an error.
     */
    private List<Expression> arguments(Expr.Call c, String name, List<Type> types, List<Boolean> references) {
        if (c.args().size() != types.size()) {
            return error(c.pos(), "'" + name + "' takes " + types.size() + " argument" + (types.size() == 1 ? "" : "s")
                    + ", not " + c.args().size());
        }
        List<Expression> args = new ArrayList<>();
        boolean ok = true;
        for (int i = 0; i < types.size(); i++) {
            Expr argExpr = c.args().get(i);
            Expression arg = compile(argExpr);
            if (arg == null) {
                ok = false;
                continue;
            }
            boolean reference = references != null && references.get(i);
            if (reference ? !isLvalue(arg) || !sameReferenceType(types.get(i), arg.type())
                    : !assignable(types.get(i), arg)) {
                error(argExpr.pos(), "argument " + (i + 1) + " of '" + name + "' must be " + types.get(i)
                        + (reference ? " (a variable: it is passed by reference)" : "") + ", not "
                        + describe(arg.type()));
                ok = false;
            } else if (!reference && isClockValue(arg.type())) {
                unsupportedClockArithmetic(argExpr.pos());
            }
            args.add(arg);
        }
        return ok ? args : null;
    }

    private void unsupportedDynamic(Pos pos) {
        compilation.unsupported(pos, "dynamic templates (spawn, exit, numOf)", "the engine runs the fixed set of"
                + " processes of the system line");
    }

    /** {@code exit()} ends a spawned process; {@code numOf(T)} counts the processes of dynamic template T. */
    private Expression dynamicBuiltin(Expr.Call c, String name) {
        if (name.equals("exit")) {
            if (!c.args().isEmpty()) {
                return error(c.pos(), "'exit' takes no arguments");
            }
            unsupportedDynamic(c.pos());
            return new Expression.Builtin(c.pos(), Type.Void.INSTANCE, name, List.of());
        }
        if (c.args().size() != 1 || !(c.args().get(0) instanceof Expr.Ident t)) {
            return error(c.pos(), "'numOf' takes the name of a dynamic template");
        }
        if (!compilation.dynamicTemplates.contains(t.name())) {
            return error(t.pos(), "'" + t.name() + "' is not a dynamic template (declare it: dynamic " + t.name()
                    + "(...);)");
        }
        unsupportedDynamic(c.pos());
        return new Expression.Builtin(c.pos(), Type.Int.UNBOUNDED, name + " " + t.name(), List.of());
    }

    /** {@code spawn T(args)}: T must be a dynamic template, and the arguments fit its parameters. */
    private Expression spawn(Expr.Spawn s) {
        Symbol sym = scope.lookup(s.template());
        if (!(sym instanceof Symbol.Template t) || !compilation.dynamicTemplates.contains(s.template())) {
            return error(s.templatePos(), "'" + s.template() + "' is not a dynamic template (declare it: dynamic "
                    + s.template() + "(...);)");
        }
        List<io.dtron.xta.ast.Param> params = t.decl().params();
        if (params.size() != s.args().size()) {
            return error(s.pos(), "'" + s.template() + "' takes " + params.size() + " argument"
                    + (params.size() == 1 ? "" : "s") + ", not " + s.args().size());
        }
        List<Expression> args = new ArrayList<>();
        for (Expr a : s.args()) {
            Expression x = compile(a);
            if (x == null) {
                return null;
            }
            args.add(x);
        }
        unsupportedDynamic(s.pos());
        return new Expression.Builtin(s.pos(), Type.Int.UNBOUNDED, "spawn " + s.template(), args);
    }

    private Expression unary(Expr.Unary u) {
        switch (u.op()) {
            case PRE_INC, PRE_DEC, POST_INC, POST_DEC -> {
                Expression target = compile(u.operand());
                if (target == null || !checkAssignable(u.operand(), target)) {
                    return null;
                }
                if (!isInteger(target.type())) {
                    return error(u.pos(), "'" + u.op().symbol() + "' needs an integer variable, not "
                            + describe(target.type()));
                }
                boolean prefix = u.op() == Expr.UnaryOp.PRE_INC || u.op() == Expr.UnaryOp.PRE_DEC;
                int delta = u.op() == Expr.UnaryOp.PRE_INC || u.op() == Expr.UnaryOp.POST_INC ? 1 : -1;
                return new Expression.Increment(u.pos(), Type.Int.UNBOUNDED, target, prefix, delta);
            }
            case PRIME -> {
                return error(u.pos(), "a clock rate (x') can only stand in an invariant, as x' == expression");
            }
            default -> {
                // NEG, PLUS, NOT below
            }
        }
        Expression operand = compile(u.operand());
        if (operand == null) {
            return null;
        }
        if (u.op() == Expr.UnaryOp.NOT) {
            if (operand.type() instanceof Type.ClockConstraint) {
                return new Expression.Unary(u.pos(), new Type.ClockConstraint(ConstraintKind.CONSTRAINT),
                        Operator.NOT, operand);
            }
            if (!isInteger(operand.type())) {
                return error(u.pos(), "'!' needs a boolean or integer, not " + describe(operand.type()));
            }
            return fold(new Expression.Unary(u.pos(), Type.Bool.INSTANCE, Operator.NOT, operand));
        }
        if (operand.type() instanceof Type.Double || isClockValue(operand.type()) && u.op() == Expr.UnaryOp.NEG) {
            if (isClockValue(operand.type())) {
                unsupportedClockArithmetic(u.pos());
            }
            return u.op() == Expr.UnaryOp.PLUS ? operand
                    : new Expression.Unary(u.pos(), Type.Double.INSTANCE, Operator.NEG, operand);
        }
        if (!isInteger(operand.type())) {
            return error(u.pos(), "'" + u.op().symbol() + "' needs an integer, not " + describe(operand.type()));
        }
        if (u.op() == Expr.UnaryOp.PLUS) {
            return operand;
        }
        return fold(new Expression.Unary(u.pos(), Type.Int.UNBOUNDED, Operator.NEG, operand));
    }

    private Expression binary(Expr.Binary b) {
        if (b.op() == Expr.BinaryOp.EQ && b.left() instanceof Expr.Unary u && u.op() == Expr.UnaryOp.PRIME) {
            return rate(b, u);
        }
        Expression left = compile(b.left());
        Expression right = compile(b.right());
        if (left == null || right == null) {
            return null;
        }
        Operator op = operator(b.op());
        Pos pos = b.pos();
        if (b.op().isComparison()) {
            return comparison(b, op, left, right);
        }
        switch (op) {
            case AND, OR, IMPLY -> {
                boolean lc = left.type() instanceof Type.ClockConstraint;
                boolean rc = right.type() instanceof Type.ClockConstraint;
                if (!lc && !isInteger(left.type()) || !rc && !isInteger(right.type())) {
                    Expression bad = !lc && !isInteger(left.type()) ? left : right;
                    return error(bad.pos(), "'" + b.op().symbol() + "' needs booleans or clock constraints, not "
                            + describe(bad.type()));
                }
                if (!lc && !rc) {
                    return fold(new Expression.Binary(pos, Type.Bool.INSTANCE, op, left, right));
                }
                ConstraintKind kind = ConstraintKind.CONSTRAINT;
                if (op == Operator.AND) {
                    kind = combine(kindOf(left), kindOf(right));
                } else if (op == Operator.OR && lc != rc) {
                    // as in Uppaal: a condition on data or a guard is still a guard
                    kind = lc ? kindOf(left) : kindOf(right);
                }
                return new Expression.Binary(pos, new Type.ClockConstraint(kind), op, left, right);
            }
            case ADD, SUB -> {
                Type lt = left.type();
                Type rt = right.type();
                boolean li = lt instanceof Type.Int;
                boolean ri = rt instanceof Type.Int;
                Type clockish = null;
                if (op == Operator.SUB && lt instanceof Type.Clock && rt instanceof Type.Clock) {
                    clockish = Type.ClockDifference.INSTANCE;
                } else if (lt instanceof Type.Clock && ri || op == Operator.ADD && li && rt instanceof Type.Clock) {
                    clockish = Type.Clock.INSTANCE;
                } else if (lt instanceof Type.ClockDifference && ri
                        || li && rt instanceof Type.ClockDifference) {
                    clockish = Type.ClockDifference.INSTANCE;
                }
                if (clockish != null) {
                    return new Expression.Binary(pos, clockish, op, left, right);
                }
            }
            default -> {
                // arithmetic below
            }
        }
        if (isReal(left.type()) && isNumberOrClock(right.type()) || isReal(right.type()) && isNumberOrClock(left.type())) {
            return doubleArithmetic(b, op, left, right);
        }
        for (Expression x : List.of(left, right)) {
            if (!isInteger(x.type())) {
                String hint = isClockValue(x.type()) ? CLOCK_HINT : "";
                return error(x.pos(), "'" + b.op().symbol() + "' needs integers, not " + describe(x.type()) + hint);
            }
        }
        return fold(new Expression.Binary(pos, Type.Int.UNBOUNDED, op, left, right));
    }

    /**
     * {@code x' == e}: the rate of clock {@code x}, an integer, a double, or (statistical model checking) a clock
     * or real-valued expression of clocks, as in {@code x' == y} (0 stops the clock).
     */
    private Expression rate(Expr.Binary b, Expr.Unary prime) {
        Expression clock = compile(prime.operand());
        Expression rate = compile(b.right());
        if (clock == null || rate == null) {
            return null;
        }
        if (!(clock.type() instanceof Type.Clock) || !isNumberOrClock(rate.type())) {
            return error(b.pos(), "a rate is written x' == expression, with a clock x and a number, not "
                    + describe(clock.type()) + " and " + describe(rate.type()));
        }
        if (!isInteger(rate.type())) {
            compilation.unsupported(b.pos(), "a clock rate given by a clock or a real number", "rates between clocks"
                    + " and real-valued rates belong to statistical model checking, and the engine's zones let clocks"
                    + " run at rate 1");
        }
        return new Expression.ClockRate(b.pos(), new Type.ClockConstraint(ConstraintKind.INVARIANT), clock, rate);
    }

    /**
     * Arithmetic with a double or a clock operand (other than a clock plus or minus an integer, or the difference
     * of two clocks) gives a double, as in Uppaal: {@code x * 2}, {@code 2.5 - x}, {@code x + y}.
     */
    private Expression doubleArithmetic(Expr.Binary b, Operator op, Expression left, Expression right) {
        return switch (op) {
            case ADD, SUB, MUL, DIV, POW, MIN, MAX -> {
                if (isClockValue(left.type()) || isClockValue(right.type())) {
                    unsupportedClockArithmetic(b.pos());
                }
                yield new Expression.Binary(b.pos(), Type.Double.INSTANCE, op, left, right);
            }
            default -> {
                Expression bad = isInteger(left.type()) ? right : left;
                yield error(bad.pos(), "'" + b.op().symbol() + "' needs integers, not " + describe(bad.type())
                        + (isClockValue(bad.type()) ? CLOCK_HINT : ""));
            }
        };
    }

    private static final String CLOCK_HINT =
            " (clocks can only be compared with integers, as in x < 5 or x - y <= 3, or reset, as in x = 0)";

    /** A clock or a clock difference: a real number in Uppaal's arithmetic on doubles. */
    static boolean isClockValue(Type t) {
        return t instanceof Type.Clock || t instanceof Type.ClockDifference;
    }

    /** A double, a clock or a clock difference: what makes arithmetic real-valued. */
    private static boolean isReal(Type t) {
        return t instanceof Type.Double || isClockValue(t);
    }

    /** Integers, booleans, doubles, clocks and clock differences: Uppaal's numbers. */
    static boolean isNumberOrClock(Type t) {
        return isNumber(t) || isClockValue(t);
    }

    private void unsupportedClockArithmetic(Pos pos) {
        compilation.unsupported(pos, "a clock used as a real number", "clocks used as real numbers (in arithmetic on"
                + " doubles, or passed as a double) belong to statistical model checking, and the engine treats clocks"
                + " symbolically, as zones");
    }

    private Expression comparison(Expr.Binary b, Operator op, Expression left, Expression right) {
        Type lt = left.type();
        Type rt = right.type();
        Pos pos = b.pos();
        if (lt.isIntegral() && rt.isIntegral()) {
            boolean ls = lt instanceof Type.Scalar;
            boolean rs = rt instanceof Type.Scalar;
            if (ls || rs) {
                if (!(ls && rs) || ((Type.Scalar) lt).id() != ((Type.Scalar) rt).id()) {
                    return error(pos, "a scalar value can only be compared with a value of the same scalar set");
                }
                if (op != Operator.EQ && op != Operator.NE) {
                    return error(pos, "scalar values can only be compared with == and !=");
                }
            }
            return fold(new Expression.Binary(pos, Type.Bool.INSTANCE, op, left, right));
        }
        boolean lClock = isClockValue(lt);
        boolean rClock = isClockValue(rt);
        if ((op == Operator.EQ || op == Operator.NE) && (lt instanceof Type.Array || lt instanceof Type.Struct)) {
            return compareAggregates(b, op, left, right);
        }
        if (!lClock && !rClock && isNumber(lt) && isNumber(rt)) {
            // one of them is a double
            return new Expression.Binary(pos, Type.Bool.INSTANCE, op, left, right);
        }
        boolean lDouble = lt instanceof Type.Double;
        boolean rDouble = rt instanceof Type.Double;
        if (lClock && rDouble || lDouble && rClock) {
            // as in Uppaal: x <= 2.5 (and 2.5 <= x) may stand in an invariant, x >= 2.5 and x == 2.5 only in guards,
            // and x != 2.5 is a condition evaluated on the clock's real value
            ConstraintKind kind = switch (op) {
                case LT, LE -> ConstraintKind.INVARIANT;
                case GE, GT -> ConstraintKind.GUARD;
                case EQ -> ConstraintKind.GUARD;
                default -> null;
            };
            if (kind == null) {
                unsupportedClockArithmetic(pos);
                return new Expression.Binary(pos, Type.Bool.INSTANCE, op, left, right);
            }
            return new Expression.Binary(pos, new Type.ClockConstraint(kind), op, left, right);
        }
        // clocks are compared with integers (not booleans), with clocks, or as differences with integers
        if (lClock && rt instanceof Type.Int || lt instanceof Type.Int && rClock
                || lt instanceof Type.Clock && rt instanceof Type.Clock) {
            ConstraintKind kind = switch (op) {
                case LT, LE, GE, GT -> ConstraintKind.INVARIANT;
                case EQ -> ConstraintKind.GUARD;
                default -> ConstraintKind.CONSTRAINT;
            };
            return new Expression.Binary(pos, new Type.ClockConstraint(kind), op, left, right);
        }
        Expression bad = !lt.isIntegral() && !lClock ? left : right;
        return error(bad.pos(), "'" + b.op().symbol() + "' cannot compare " + describe(lt) + " with "
                + describe(rt) + (lClock || rClock ? "; a clock is compared with an integer, as in x <= 5" : ""));
    }

    /**
     * {@code a == b} and {@code a != b} on arrays and structs of the same type, element by element, as Uppaal
     * compares them; the engine compares single values only.
     */
    private Expression compareAggregates(Expr.Binary b, Operator op, Expression left, Expression right) {
        Type lt = left.type();
        if (!sameType(lt, right.type()) || lt.clocks() > 0 || lt.channels() > 0) {
            return error(b.pos(), "'" + b.op().symbol() + "' compares arrays and structs of the same type (the same"
                    + " size, element type and ranges), not " + describe(lt) + " and " + describe(right.type()));
        }
        compilation.unsupported(b.pos(), "'==' and '!=' on arrays and structs", "the engine compares single values;"
                + " compare the elements one by one");
        return new Expression.Binary(b.pos(), Type.Bool.INSTANCE, op, left, right);
    }

    private static ConstraintKind kindOf(Expression e) {
        return e.type() instanceof Type.ClockConstraint c ? c.kind() : null;
    }

    private static ConstraintKind combine(ConstraintKind a, ConstraintKind b) {
        if (a == null) {
            return b;
        }
        if (b == null) {
            return a;
        }
        return a.compareTo(b) >= 0 ? a : b;
    }

    private Expression conditional(Expr.Conditional c) {
        Expression cond = compile(c.condition());
        Expression then = compile(c.then());
        Expression otherwise = compile(c.otherwise());
        if (cond == null || then == null || otherwise == null) {
            return null;
        }
        if (!isInteger(cond.type())) {
            return error(c.condition().pos(), "the condition of '?:' must be a boolean, not " + describe(cond.type()));
        }
        Type type;
        if (then.type() instanceof Type.Bool && otherwise.type() instanceof Type.Bool) {
            type = Type.Bool.INSTANCE;
        } else if (isInteger(then.type()) && isInteger(otherwise.type())) {
            type = Type.Int.UNBOUNDED;
        } else if (then.type().isIntegral() && sameType(then.type(), otherwise.type())) {
            type = then.type();
        } else if (isNumberOrClock(then.type()) && isNumberOrClock(otherwise.type())) {
            // a double or a clock in either branch makes a double, as in Uppaal: b ? 1.5 : 2, b ? x : 0
            if (isClockValue(then.type()) || isClockValue(otherwise.type())) {
                unsupportedClockArithmetic(c.pos());
            }
            type = Type.Double.INSTANCE;
        } else {
            return error(c.pos(), "both branches of '?:' must be integers or booleans, not " + describe(then.type())
                    + " and " + describe(otherwise.type()));
        }
        if (cond instanceof Expression.Constant k) {
            return k.value() != 0 ? then : otherwise;
        }
        return new Expression.Conditional(c.pos(), type, cond, then, otherwise);
    }

    private Expression assign(Expr.Assign a) {
        Expression target = compile(a.target());
        Expression value = compile(a.value());
        if (target == null || value == null || !checkAssignable(a.target(), target)) {
            return null;
        }
        Operator op = a.op() == null ? null : operator(a.op());
        if (target.type() instanceof Type.Clock) {
            if (op != null) {
                return error(a.pos(), "a clock can only be reset with '=', as in x = 0");
            }
            if (isReal(value.type())) {
                // Uppaal accepts x = 1.5, x = d and x = y: statistical model checking sets clocks to real values
                compilation.unsupported(a.pos(), "a clock set to a real number or to another clock", "the engine"
                        + " resets clocks to integers, as zones need");
                return new Expression.Assign(a.pos(), Type.Clock.INSTANCE, target, null, value);
            }
            if (!isInteger(value.type())) {
                return error(a.value().pos(), "a clock is set to a number or a clock, not to " + describe(value.type()));
            }
            if (value instanceof Expression.Constant k && k.value() < 0) {
                return error(a.value().pos(), "a clock cannot be reset to a negative value (" + k.value() + ")");
            }
            return new Expression.Assign(a.pos(), Type.Clock.INSTANCE, target, null, value);
        }
        if (target.type() instanceof Type.Double) {
            if (!isNumberOrClock(value.type())) {
                return error(a.value().pos(), "cannot assign " + describe(value.type()) + " to the double '"
                        + a.target().pos().text() + "'");
            }
            if (isClockValue(value.type())) {
                unsupportedClockArithmetic(a.value().pos());
            }
            return new Expression.Assign(a.pos(), target.type(), target, op, value);
        }
        if (op != null) {
            if (!isInteger(target.type()) || !isInteger(value.type())) {
                return error(a.pos(), "'" + a.op().symbol() + "=' needs integers");
            }
        } else if (!assignable(target.type(), value)) {
            return error(a.value().pos(), "cannot assign " + describe(value.type()) + " to '" + a.target().pos().text()
                    + "' of type " + target.type());
        } else {
            warnIfOutOfRange(a.value().pos(), target.type(), value, "'" + a.target().pos().text() + "'");
        }
        return new Expression.Assign(a.pos(), target.type(), target, op, value);
    }

    /** The values a bound name takes: a resolved bounded integer range or scalar set, with its limits. */
    record Range(Type type, int lower, int upper) {
    }

    /**
     * The range of a quantifier, a select binding or a {@code for (i : T)} loop: {@code t} must be a bounded
     * integer range or a scalar set; otherwise an error "{@code what} needs ..." and null.
     */
    Range boundedRange(TypeExpr t, String what) {
        Resolved r = resolve(t);
        if (r == null) {
            return null;
        }
        if (r.type() instanceof Type.Int i && !i.equals(Type.Int.DEFAULT)) {
            return new Range(r.type(), i.lower(), i.upper());
        }
        if (r.type() instanceof Type.Scalar s) {
            return new Range(r.type(), 0, s.size() - 1);
        }
        return error(t.pos(), what + " needs a bounded integer range or a scalar set, not " + r.type());
    }

    private Expression quantifier(Expr.Quantifier q) {
        Range range = boundedRange(q.type(), "a quantifier");
        if (range == null) {
            return null;
        }
        int lower = range.lower();
        int upper = range.upper();
        int slot = frame.allocate(1);
        Scope outer = scope;
        Scope inner = new Scope(outer);
        inner.put(q.name(), new Symbol.Local(q.pos(), range.type(), slot, false, false));
        scope = inner;
        Expression body;
        try {
            body = compile(q.body());
        } finally {
            scope = outer;
        }
        if (body == null) {
            return null;
        }
        Expression.Quantifier kind = Expression.Quantifier.valueOf(q.kind().name());
        if (body.type() instanceof Type.ClockConstraint c && kind != Expression.Quantifier.SUM) {
            // forall is a conjunction, so it keeps the body's kind; exists is a disjunction of clock constraints
            compilation.unsupported(q.pos(), "'" + q.kind().name().toLowerCase(java.util.Locale.ROOT)
                    + "' over clock constraints", "the engine's zones take conjunctions of single clock bounds, written"
                    + " out");
            ConstraintKind k = kind == Expression.Quantifier.FORALL ? c.kind() : ConstraintKind.CONSTRAINT;
            return new Expression.Quantified(q.pos(), new Type.ClockConstraint(k), kind, slot, lower, upper, body);
        }
        if (!isInteger(body.type())) {
            return error(q.body().pos(), "the body of '" + q.kind().name().toLowerCase(java.util.Locale.ROOT)
                    + "' must be " + (q.kind() == Expr.QuantifierKind.SUM ? "an integer" : "a boolean") + ", not "
                    + describe(body.type()));
        }
        Type type = kind == Expression.Quantifier.SUM ? Type.Int.UNBOUNDED : Type.Bool.INSTANCE;
        return new Expression.Quantified(q.pos(), type, kind, slot, lower, upper, body);
    }

    // ================================================================ checks shared with declarations

    /** Whether a value of {@code value}'s type may be stored in {@code target}. */
    static boolean assignable(Type target, Expression value) {
        Type v = value.type();
        if (target instanceof Type.Int || target instanceof Type.Bool) {
            return isInteger(v);
        }
        if (target instanceof Type.Double) {
            return isNumberOrClock(v);
        }
        if (target instanceof Type.Str) {
            return v instanceof Type.Str;
        }
        if (target instanceof Type.Scalar s) {
            return v instanceof Type.Scalar vs && vs.id() == s.id();
        }
        if (target instanceof Type.Clock) {
            return isNumberOrClock(v);
        }
        if (target instanceof Type.Array || target instanceof Type.Struct) {
            return sameType(target, v);
        }
        return false;
    }

    /**
     * Whether {@code value} may initialise a variable of type {@code target}: as {@link #assignable}, but a clock
     * initialises no double or clock (Uppaal's rule: an initialiser is computable at compile time).
     */
    static boolean initialisable(Type target, Expression value) {
        return assignable(target, value) && !isClockValue(value.type());
    }

    /** Equality of types for references and whole-array assignment; integer ranges must agree. */
    static boolean sameType(Type a, Type b) {
        return a.equals(b);
    }

    /**
     * The rule for reference parameters: exactly the parameter's type, except that a channel (or an array of
     * channels) of any kind may be passed where a channel of another kind is expected, as Uppaal's type checker
     * accepts (a {@code broadcast chan} for an {@code urgent chan &} parameter).
     */
    static boolean sameReferenceType(Type parameter, Type argument) {
        if (parameter instanceof Type.Channel && argument instanceof Type.Channel) {
            return true;
        }
        if (parameter instanceof Type.Array p && argument instanceof Type.Array a) {
            return p.index().equals(a.index()) && sameReferenceType(p.element(), a.element());
        }
        return sameType(parameter, argument);
    }

    /**
     * Whether {@code e} reads no variable and no clock, so that its value is known when the model loads (used for
     * the initial values of doubles and clocks; integer ones are evaluated).
     */
    static boolean computable(Expression e) {
        if (e instanceof Expression.VariableRef || e instanceof Expression.ClockRef) {
            return false;
        } else if (e instanceof Expression.Index i) {
            return computable(i.array()) && computable(i.index());
        } else if (e instanceof Expression.FieldRef f) {
            return computable(f.struct());
        } else if (e instanceof Expression.Unary u) {
            return computable(u.operand());
        } else if (e instanceof Expression.Binary b) {
            return computable(b.left()) && computable(b.right());
        } else if (e instanceof Expression.Conditional c) {
            return computable(c.condition()) && computable(c.then()) && computable(c.otherwise());
        } else if (e instanceof Expression.Call c) {
            return c.args().stream().allMatch(Checker::computable);
        } else if (e instanceof Expression.Builtin b) {
            return b.args().stream().allMatch(Checker::computable);
        } else if (e instanceof Expression.Quantified q) {
            return computable(q.body());
        }
        return true;
    }

    /** Integers, booleans and doubles. */
    static boolean isNumber(Type t) {
        return isInteger(t) || t instanceof Type.Double;
    }

    /** Integers and booleans, not scalars. */
    static boolean isInteger(Type t) {
        return t instanceof Type.Int || t instanceof Type.Bool;
    }

    void warnIfOutOfRange(Pos pos, Type target, Expression value, String what) {
        if (target instanceof Type.Int i && value instanceof Expression.Constant c
                && (c.value() < i.lower() || c.value() > i.upper())) {
            diagnostics.warning(pos, "the value " + c.value() + " is outside the range of " + what + " (" + i
                    + "); assigning it is a model error");
        }
    }

    static boolean isLvalue(Expression e) {
        if (e instanceof Expression.VariableRef || e instanceof Expression.ClockRef
                || e instanceof Expression.ChannelRef || e instanceof Expression.LocalRef) {
            return true;
        }
        if (e instanceof Expression.Index i) {
            return isLvalue(i.array());
        }
        return e instanceof Expression.FieldRef f && isLvalue(f.struct());
    }

    /** Why the AST expression cannot be assigned to, or null when it can. */
    String notAssignable(Expr target) {
        Expr root = target;
        while (true) {
            if (root instanceof Expr.Index i) {
                root = i.array();
            } else if (root instanceof Expr.Field f) {
                root = f.value();
            } else {
                break;
            }
        }
        if (!(root instanceof Expr.Ident id)) {
            return "it is not a variable";
        }
        Symbol sym = scope.lookup(id.name());
        if (sym == null || sym instanceof Symbol.Var || sym instanceof Symbol.ClockVar) {
            return null;
        } else if (sym instanceof Symbol.Constant) {
            return "'" + id.name() + "' is a constant";
        } else if (sym instanceof Symbol.ChanVar) {
            return "'" + id.name() + "' is a channel";
        } else if (sym instanceof Symbol.Local l) {
            return l.assignable() ? null : "'" + id.name() + "' cannot be assigned here";
        } else if (sym instanceof Symbol.FreeParam f) {
            return "'" + id.name() + "' is a free parameter of " + f.owner()
                    + ": the system line makes one process per value of " + f.type()
                    + ", so it is a constant in each; use a local variable initialised from it instead";
        } else if (sym instanceof Symbol.Alias a) {
            return a.assignable() ? null : "'" + id.name() + "' is a constant"
                    + (a.target().type() instanceof Type.Double ? "" : " parameter");
        }
        return "'" + id.name() + "' is not a variable";
    }

    private boolean checkAssignable(Expr targetAst, Expression target) {
        String why = notAssignable(targetAst);
        if (why == null && !isLvalue(target)) {
            why = "it is not a variable";
        }
        if (why == null && target.type() instanceof Type.Channel) {
            why = "channels cannot be assigned";
        }
        if (why != null) {
            diagnostics.error(targetAst.pos(), "cannot assign to '" + targetAst.pos().text() + "': " + why);
            return false;
        }
        return true;
    }

    /** Whether evaluating {@code e} may change a variable, a clock or anything outside its frame. */
    boolean hasSideEffects(Expression e) {
        if (e instanceof Expression.Assign || e instanceof Expression.Increment) {
            return true;
        } else if (e instanceof Expression.Call c) {
            return !compilation.function(c.function()).sideEffectFree
                    || c.args().stream().anyMatch(this::hasSideEffects);
        } else if (e instanceof Expression.Index i) {
            return hasSideEffects(i.array()) || hasSideEffects(i.index());
        } else if (e instanceof Expression.FieldRef f) {
            return hasSideEffects(f.struct());
        } else if (e instanceof Expression.Unary u) {
            return hasSideEffects(u.operand());
        } else if (e instanceof Expression.Binary b) {
            return hasSideEffects(b.left()) || hasSideEffects(b.right());
        } else if (e instanceof Expression.Conditional c) {
            return hasSideEffects(c.condition()) || hasSideEffects(c.then()) || hasSideEffects(c.otherwise());
        } else if (e instanceof Expression.Quantified q) {
            return hasSideEffects(q.body());
        } else if (e instanceof Expression.ClockRate r) {
            return hasSideEffects(r.rate());
        } else if (e instanceof Expression.Builtin b) {
            return b.name().startsWith("spawn ") || b.name().equals("exit")
                    || b.args().stream().anyMatch(this::hasSideEffects);
        }
        return false;
    }

    static String describe(Type t) {
        if (t instanceof Type.ClockConstraint) {
            return "a clock constraint";
        }
        if (t instanceof Type.Clock) {
            return "a clock";
        }
        if (t instanceof Type.Channel c) {
            return "a " + c;
        }
        if (t instanceof Type.Array) {
            return "an array (" + t + ")";
        }
        if (t instanceof Type.Struct) {
            return "a struct";
        }
        if (t instanceof Type.Int) {
            return "an integer";
        }
        if (t instanceof Type.Bool) {
            return "a boolean";
        }
        if (t instanceof Type.Scalar s) {
            return "a value of " + s;
        }
        if (t instanceof Type.Void) {
            return "nothing (void)";
        }
        if (t instanceof Type.Double) {
            return "a double";
        }
        if (t instanceof Type.Str) {
            return "a string";
        }
        return "a " + t;
    }

    private static Operator operator(Expr.BinaryOp op) {
        return switch (op) {
            case POW -> Operator.POW;
            case MUL -> Operator.MUL;
            case DIV -> Operator.DIV;
            case MOD -> Operator.MOD;
            case ADD -> Operator.ADD;
            case SUB -> Operator.SUB;
            case SHL -> Operator.SHL;
            case SHR -> Operator.SHR;
            case MIN -> Operator.MIN;
            case MAX -> Operator.MAX;
            case LT -> Operator.LT;
            case LE -> Operator.LE;
            case GE -> Operator.GE;
            case GT -> Operator.GT;
            case EQ -> Operator.EQ;
            case NE -> Operator.NE;
            case BIT_AND -> Operator.BIT_AND;
            case BIT_XOR -> Operator.BIT_XOR;
            case BIT_OR -> Operator.BIT_OR;
            case AND -> Operator.AND;
            case OR -> Operator.OR;
            case IMPLY -> Operator.IMPLY;
        };
    }

    // ================================================================ folding

    private Expression fold(Expression e) {
        if (e instanceof Expression.Unary u && u.operand() instanceof Expression.Constant c) {
            int v = u.op() == Operator.NEG ? -c.value() : (c.value() == 0 ? 1 : 0);
            return new Expression.Constant(e.pos(), e.type(), v);
        }
        if (e instanceof Expression.Binary b && b.left() instanceof Expression.Constant l
                && b.right() instanceof Expression.Constant r) {
            long x = l.value();
            long y = r.value();
            long v;
            switch (b.op()) {
                case ADD -> v = x + y;
                case SUB -> v = x - y;
                case MUL -> v = x * y;
                case DIV, MOD -> {
                    if (y == 0) {
                        diagnostics.warning(e.pos(), "division by zero; evaluating it is a model error");
                        return new Expression.ModelError(e.pos(), e.type(), "division by zero");
                    }
                    v = b.op() == Operator.DIV ? x / y : x % y;
                }
                case POW -> {
                    if (y < 0) {
                        diagnostics.warning(e.pos(), "negative exponent; evaluating it is a model error");
                        return new Expression.ModelError(e.pos(), e.type(), "negative exponent");
                    }
                    v = power(x, y);
                }
                case SHL -> v = (long) l.value() << r.value();
                case SHR -> v = l.value() >> r.value();
                case MIN -> v = Math.min(x, y);
                case MAX -> v = Math.max(x, y);
                case BIT_AND -> v = x & y;
                case BIT_OR -> v = x | y;
                case BIT_XOR -> v = x ^ y;
                case LT -> v = x < y ? 1 : 0;
                case LE -> v = x <= y ? 1 : 0;
                case EQ -> v = x == y ? 1 : 0;
                case NE -> v = x != y ? 1 : 0;
                case GE -> v = x >= y ? 1 : 0;
                case GT -> v = x > y ? 1 : 0;
                case AND -> v = x != 0 && y != 0 ? 1 : 0;
                case OR -> v = x != 0 || y != 0 ? 1 : 0;
                case IMPLY -> v = x == 0 || y != 0 ? 1 : 0;
                default -> {
                    return e;
                }
            }
            if (v < Integer.MIN_VALUE || v > Integer.MAX_VALUE) {
                diagnostics.warning(e.pos(), "integer overflow; evaluating it is a model error");
                return new Expression.ModelError(e.pos(), e.type(), "integer overflow");
            }
            return new Expression.Constant(e.pos(), e.type(), (int) v);
        }
        return e;
    }

    /** {@code x ** y} for {@code y >= 0}, saturated past the range of int so that an overflow is seen. */
    static long power(long x, long y) {
        long r = 1;
        for (long i = 0; i < y; i++) {
            r *= x;
            if (Math.abs(r) > Integer.MAX_VALUE + 1L) {
                return r;
            }
            if (r == 0 || r == 1 && x == 1) {
                return r;
            }
            if (x == -1) {
                return y % 2 == 0 ? 1 : -1;
            }
        }
        return r;
    }
}

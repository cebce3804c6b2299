package io.dtron.model.internal;

import io.dtron.model.Expression;
import io.dtron.model.Function;
import io.dtron.model.Statement;
import io.dtron.model.Type;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Initializer;
import io.dtron.xta.ast.Param;
import io.dtron.xta.ast.TypeExpr;
import java.util.ArrayList;
import java.util.List;

/** Declarations of variables, constants, clocks, channels, typedefs and functions, global or in a template. */
final class DeclarationCompiler {
    private final Compilation compilation;
    private final Diagnostics diagnostics;

    DeclarationCompiler(Compilation compilation) {
        this.compilation = compilation;
        this.diagnostics = compilation.diagnostics;
    }

    /**
     * Declares {@code decls} into the checker's scope. {@code owner} is the process they belong to (null for
     * globals); templates, instantiations and channel priorities are handed to {@code others}.
     */
    void declare(List<Decl> decls, Checker checker, String owner, List<Decl> others) {
        for (Decl d : decls) {
            if (d instanceof Decl.Variable v) {
                variable(v, checker, owner);
            } else if (d instanceof Decl.Typedef t) {
                Checker.Resolved r = checker.resolve(t.type());
                if (r != null && declarable(checker.scope(), t.name(), t.pos())) {
                    Type type = checker.applyDims(r.type(), t.dims());
                    if (type != null) {
                        checker.scope().put(t.name(), new Symbol.TypeName(t.pos(), type, r.constant()));
                    }
                }
            } else if (d instanceof Decl.Function f) {
                function(f, checker, owner);
            } else if (d instanceof Decl.External x) {
                external(x, checker);
            } else if (d instanceof Decl.Dynamic dynamic && others != null) {
                if (!compilation.dynamicTemplates.add(dynamic.name())) {
                    diagnostics.error(dynamic.pos(), "dynamic template '" + dynamic.name() + "' is declared twice");
                }
            } else if (others != null) {
                if (d instanceof Decl.Template t && declarable(checker.scope(), t.name(), t.pos())) {
                    checker.scope().put(t.name(), new Symbol.Template(t.pos(), t));
                } else if (d instanceof Decl.Instantiation i && declarable(checker.scope(), i.name(), i.pos())) {
                    checker.scope().put(i.name(), new Symbol.Instantiation(i.pos(), i));
                }
                others.add(d);
            } else {
                diagnostics.error(d.pos(), d instanceof Decl.ChanPriority
                        ? "channel priorities can only be declared globally"
                        : d instanceof Decl.Dynamic ? "dynamic templates can only be declared globally"
                        : "templates and instantiations can only be declared globally");
            }
        }
    }

    /** An external function of an {@code import} block: its signature is checked, its calls are type-checked. */
    private void external(Decl.External x, Checker checker) {
        Checker.Resolved ret = checker.resolve(x.returnType());
        if (ret == null || !declarable(checker.scope(), x.name(), x.pos())) {
            return;
        }
        List<Type> types = new ArrayList<>();
        List<Boolean> references = new ArrayList<>();
        for (Param p : x.params()) {
            // a library may take strings (Uppaal passes them as C strings); no other declaration has that type
            Checker.Resolved r = p.type() instanceof TypeExpr.NamedType n && n.name().equals("string")
                    && !(checker.scope().lookup("string") instanceof Symbol.TypeName)
                    ? new Checker.Resolved(Type.Str.INSTANCE, true, false) : checker.resolve(p.type());
            Type t = r == null ? null : checker.applyDims(r.type(), p.dims());
            if (t == null) {
                return;
            }
            types.add(t);
            // a string is passed as a C string whether or not it is declared const string&
            references.add(p.reference() && !(t instanceof Type.Str));
        }
        checker.scope().put(x.name(), new Symbol.External(x.pos(), x.name(), ret.type(), types, references,
                x.library()));
    }

    private boolean declarable(Scope scope, String name, Pos pos) {
        Symbol existing = scope.local(name);
        if (existing != null) {
            diagnostics.error(pos, "'" + name + "' is already declared"
                    + (existing.pos() == null ? "" : " at line " + existing.pos().line()));
            return false;
        }
        return true;
    }

    static String qualified(String owner, String name) {
        return owner == null ? name : owner + "." + name;
    }

    private void variable(Decl.Variable v, Checker checker, String owner) {
        Checker.Resolved r = checker.resolve(v.type());
        if (r == null) {
            return;
        }
        Type type = checker.applyDims(r.type(), v.dims());
        if (type == null || !declarable(checker.scope(), v.name(), v.pos())) {
            return;
        }
        Scope scope = checker.scope();
        if (type instanceof Type.Void) {
            diagnostics.error(v.pos(), "'" + v.name() + "' cannot be of type void");
        } else if (type.clocks() > 0) {
            if (r.constant() || r.meta()) {
                // Uppaal: "prefix const (meta) not allowed for clocks"
                diagnostics.error(v.type().pos(), (r.constant() ? "'const'" : "'meta'") + " does not apply to clocks");
                return;
            }
            if (v.init() != null && initialValues(v.init(), type, checker, "clock '" + v.name() + "'", false) != null
                    && !zero(v.init())) {
                // Uppaal (statistical model checking) starts a clock at a number computable at compile time
                compilation.unsupported(v.init().pos(), "a clock with an initial value", "the engine starts every"
                        + " clock at 0, as the zones of symbolic model checking do");
            }
            scope.put(v.name(), new Symbol.ClockVar(v.pos(),
                    compilation.newClock(qualified(owner, v.name()), type, owner, v.pos())));
        } else if (type.channels() > 0) {
            if (v.init() != null) {
                diagnostics.error(v.init().pos(), "channel '" + v.name() + "' cannot have an initialiser");
            }
            scope.put(v.name(), new Symbol.ChanVar(v.pos(),
                    compilation.newChannel(qualified(owner, v.name()), type, owner, v.pos())));
        } else if (r.constant()) {
            if (v.init() == null) {
                diagnostics.error(v.pos(), "constant '" + v.name() + "' needs a value");
                return;
            }
            if (type instanceof Type.Double) {
                Expression value = doubleConstant(v, checker);
                if (value != null) {
                    scope.put(v.name(), new Symbol.Alias(v.pos(), value, false, false, false));
                }
                return;
            }
            int[] values = initialValues(v.init(), type, checker, "'" + v.name() + "'", true);
            if (values != null) {
                scope.put(v.name(), new Symbol.Constant(v.pos(), type, values));
            }
        } else {
            int[] values = v.init() == null ? defaults(type)
                    : initialValues(v.init(), type, checker, "'" + v.name() + "'", false);
            if (values == null) {
                values = defaults(type);
            }
            scope.put(v.name(), new Symbol.Var(v.pos(), compilation.newVariable(qualified(owner, v.name()), type,
                    values, r.meta(), owner, v.pos())));
        }
    }

    /** Whether {@code init} is {@code 0}, or braces of zeros: where every clock starts anyway. */
    private static boolean zero(Initializer init) {
        if (init instanceof Initializer.Braces b) {
            return b.elements().stream().allMatch(DeclarationCompiler::zero);
        }
        return ((Initializer.Single) init).value() instanceof Expr.IntLit i && i.value() == 0;
    }

    /** The value of a {@code const double}: a number, kept as the expression (the engine does not run doubles). */
    private Expression doubleConstant(Decl.Variable v, Checker checker) {
        if (!(v.init() instanceof Initializer.Single single)) {
            diagnostics.error(v.init().pos(), "a brace list initialises arrays and structs, but '" + v.name()
                    + "' is a double");
            return null;
        }
        Expression x = checker.compile(single.value());
        if (x != null && (!Checker.isNumber(x.type()) || checker.hasSideEffects(x))) {
            diagnostics.error(single.pos(), "'" + v.name() + "' is a double and cannot be initialised with "
                    + Checker.describe(x.type()));
            return null;
        }
        if (x != null && !Checker.computable(x)) {
            diagnostics.error(single.pos(), "the initial value of '" + v.name() + "' must be computable at compile"
                    + " time");
            return null;
        }
        return x;
    }

    /** The default initial values: 0, or the lower bound of a range that excludes 0. */
    static int[] defaults(Type type) {
        int[] values = new int[type.slots()];
        fillDefaults(type, values, 0);
        return values;
    }

    private static int fillDefaults(Type type, int[] values, int offset) {
        if (type instanceof Type.Int i) {
            values[offset] = i.lower() > 0 ? i.lower() : Math.min(0, i.upper());
            return offset + 1;
        }
        if (type instanceof Type.Array a) {
            int o = offset;
            for (int k = 0; k < a.length(); k++) {
                o = fillDefaults(a.element(), values, o);
            }
            return o;
        }
        if (type instanceof Type.Struct s) {
            int o = offset;
            for (Type.Field f : s.fields()) {
                o = fillDefaults(f.type(), values, o);
            }
            return o;
        }
        return offset + type.slots();
    }

    /**
     * The initial values of a variable or constant of {@code type}: they must be computable at compile time,
     * as Uppaal requires. The range of a plain {@code int} bounds variables, not constants ({@code constant}),
     * which may take any 32-bit value. Doubles are checked but hold nothing (0). Null after an error.
     */
    int[] initialValues(Initializer init, Type type, Checker checker, String what, boolean constant) {
        if (init instanceof Initializer.Braces b) {
            if (type instanceof Type.Array a) {
                if (b.elements().size() != a.length()) {
                    diagnostics.error(b.pos(), what + " has " + a.length() + " elements, but the initialiser gives "
                            + b.elements().size());
                    return null;
                }
                int[] values = new int[type.slots()];
                int offset = 0;
                for (Initializer e : b.elements()) {
                    int[] part = initialValues(e, a.element(), checker, what, constant);
                    if (part == null) {
                        return null;
                    }
                    System.arraycopy(part, 0, values, offset, part.length);
                    offset += part.length;
                }
                return values;
            }
            if (type instanceof Type.Struct s) {
                if (b.elements().size() != s.fields().size()) {
                    diagnostics.error(b.pos(), what + " has " + s.fields().size() + " fields, but the initialiser gives "
                            + b.elements().size());
                    return null;
                }
                int[] values = new int[type.slots()];
                int offset = 0;
                for (int i = 0; i < s.fields().size(); i++) {
                    int[] part = initialValues(b.elements().get(i), s.fields().get(i).type(), checker, what,
                            constant);
                    if (part == null) {
                        return null;
                    }
                    System.arraycopy(part, 0, values, offset, part.length);
                    offset += part.length;
                }
                return values;
            }
            diagnostics.error(b.pos(), "a brace list initialises arrays and structs, but " + what + " is " + type);
            return null;
        }
        Initializer.Single single = (Initializer.Single) init;
        boolean placeholderBefore = checker.usedPlaceholder;
        boolean referenceBefore = checker.usedReference;
        checker.usedPlaceholder = false;
        checker.usedReference = false;
        Expression x = checker.compile(single.value());
        boolean placeholder = checker.usedPlaceholder;
        boolean reference = checker.usedReference;
        checker.usedPlaceholder = placeholderBefore || placeholder;
        checker.usedReference = referenceBefore || reference;
        if (x == null) {
            return null;
        }
        if (x instanceof Expression.ModelError m) {
            diagnostics.error(single.pos(), "the initial value of " + what + " cannot be computed: " + m.message());
            return null;
        }
        if (type instanceof Type.Double || type instanceof Type.Clock) {
            String kind = type instanceof Type.Double ? "a double" : "a clock";
            if (!Checker.isNumberOrClock(x.type())) {
                diagnostics.error(single.pos(), what + " is " + kind + " and cannot be initialised with "
                        + Checker.describe(x.type()));
                return null;
            }
            if (reference || !Checker.computable(x)) {
                diagnostics.error(single.pos(), "the initial value of " + what + " must be computable at compile time"
                        + (reference ? " (a reference parameter is not, even when it refers to a constant)" : ""));
                return null;
            }
            return new int[type.slots()];
        }
        if (x.type() instanceof Type.Double && !Checker.assignable(type, x)) {
            diagnostics.error(single.pos(), what + " is " + type + " and cannot be initialised with a double");
            return null;
        }
        int[] values = reference ? null : checker.constantValues(x);
        if (values == null) {
            if (placeholder) {
                return defaults(type);
            }
            diagnostics.error(single.pos(), "the initial value of " + what + " must be computable at compile time"
                    + (reference ? " (a reference parameter is not, even when it refers to a constant)" : ""));
            return null;
        }
        if (!Checker.assignable(type, x)) {
            diagnostics.error(single.pos(), what + " is " + type + " and cannot be initialised with "
                    + Checker.describe(x.type()));
            return null;
        }
        if (type instanceof Type.Int i && (values[0] < i.lower() || values[0] > i.upper())
                && !(constant && i.equals(Type.Int.DEFAULT))) {
            diagnostics.error(single.pos(), "the initial value " + values[0] + " of " + what + " is outside its range "
                    + i);
            return null;
        }
        if (type instanceof Type.Bool) {
            values[0] = values[0] != 0 ? 1 : 0;
        }
        return values;
    }

    // ================================================================ functions

    private void function(Decl.Function f, Checker outer, String owner) {
        Checker.Resolved ret = outer.resolve(f.returnType());
        if (ret == null || !declarable(outer.scope(), f.name(), f.pos())) {
            return;
        }
        if (ret.type().clocks() > 0 || ret.type().channels() > 0) {
            diagnostics.error(f.returnType().pos(), "a function cannot return " + Checker.describe(ret.type()));
            return;
        }
        Frame frame = new Frame(0);
        Scope scope = new Scope(outer.scope());
        Checker checker = new Checker(compilation, scope, frame);
        List<Function.Parameter> params = new ArrayList<>();
        for (Param p : f.params()) {
            Checker.Resolved r = checker.resolve(p.type());
            if (r == null) {
                return;
            }
            Type t = checker.applyDims(r.type(), p.dims());
            if (t == null) {
                return;
            }
            if (!p.reference() && (t.clocks() > 0 || t.channels() > 0)) {
                diagnostics.error(p.pos(), "parameter '" + p.name() + "': clocks and channels are passed by"
                        + " reference (" + t + " &" + p.name() + ")");
                return;
            }
            if (scope.local(p.name()) != null) {
                diagnostics.error(p.pos(), "parameter '" + p.name() + "' is declared twice");
                return;
            }
            int slot = frame.allocate(p.reference() ? 1 : t.slots());
            scope.put(p.name(), new Symbol.Local(p.pos(), t, slot, p.reference(), !r.constant()));
            params.add(new Function.Parameter(p.name(), t, p.reference(), slot));
        }
        String name = qualified(owner, f.name());
        FunctionInfo info = compilation.newFunction(name, ret.type(), params);
        outer.scope().put(f.name(), new Symbol.Func(f.pos(), info));
        StatementCompiler statements = new StatementCompiler(compilation, this, checker, info);
        Statement.Block body = statements.block(f.body());
        if (!(ret.type() instanceof Type.Void) && !StatementCompiler.alwaysReturns(body)) {
            diagnostics.warning(f.pos(), "function '" + f.name() + "' may end without returning a value; "
                    + "that is a model error when it happens");
        }
        compilation.completeFunction(new Function(info.index, name, owner, ret.type(), params, frame.size(), body,
                info.sideEffectFree, f.pos()));
    }

    /** Declares a block's local variable in a function frame; returns its initialisation statement or null. */
    Statement local(Decl.Variable v, Checker checker) {
        Checker.Resolved r = checker.resolve(v.type());
        if (r == null) {
            return null;
        }
        Type type = checker.applyDims(r.type(), v.dims());
        if (type == null || !declarable(checker.scope(), v.name(), v.pos())) {
            return null;
        }
        if (type.clocks() > 0 || type.channels() > 0 || type instanceof Type.Void) {
            diagnostics.error(v.pos(), "a function cannot declare " + Checker.describe(type) + " locally");
            return null;
        }
        if (r.constant()) {
            if (v.init() == null) {
                diagnostics.error(v.pos(), "constant '" + v.name() + "' needs a value");
                return null;
            }
            int[] values = initialValues(v.init(), type, checker, "'" + v.name() + "'", true);
            if (values != null) {
                checker.scope().put(v.name(), new Symbol.Constant(v.pos(), type, values));
            }
            return null;
        }
        int slot = checker.frame().allocate(type.slots());
        Expression initial = null;
        if (v.init() instanceof Initializer.Single s) {
            initial = checker.compile(s.value());
            if (initial != null && !Checker.initialisable(type, initial)) {
                diagnostics.error(s.pos(), "'" + v.name() + "' is " + type + " and cannot be initialised with "
                        + Checker.describe(initial.type()));
                initial = null;
            }
        } else if (v.init() instanceof Initializer.Braces b) {
            int[] values = initialValues(b, type, checker, "'" + v.name() + "'", false);
            if (values != null) {
                initial = new Expression.ConstantTable(b.pos(), type, values);
            }
        }
        checker.scope().put(v.name(), new Symbol.Local(v.pos(), type, slot, false, true));
        return new Statement.InitLocal(v.pos(), slot, type, initial);
    }

    /** Declares a typedef or constant inside a function block. */
    void blockDeclaration(Decl d, Checker checker, List<Statement> out) {
        if (d instanceof Decl.Variable v) {
            Statement init = local(v, checker);
            if (init != null) {
                out.add(init);
            }
        } else if (d instanceof Decl.Typedef) {
            declare(List.of(d), checker, null, null);
        } else {
            diagnostics.error(d.pos(), "only variables and typedefs can be declared inside a function body");
        }
    }
}

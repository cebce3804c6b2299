package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.ArrayDim;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Edge;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Expr.BinaryOp;
import io.dtron.xta.ast.Expr.UnaryOp;
import io.dtron.xta.ast.Initializer;
import io.dtron.xta.ast.Location;
import io.dtron.xta.ast.Param;
import io.dtron.xta.ast.Query;
import io.dtron.xta.ast.Stmt;
import io.dtron.xta.ast.SystemLine;
import io.dtron.xta.ast.TypeExpr;
import io.dtron.xta.internal.parser.UppaalParser.*;
import java.util.ArrayList;
import java.util.EnumSet;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import org.antlr.v4.runtime.ParserRuleContext;
import org.antlr.v4.runtime.Token;

/** Builds the AST of one fragment from its parse tree. */
final class AstBuilder {
    private final Fragment fragment;
    private final List<Diagnostic> diagnostics;
    private int expressionDepth;
    private boolean tooDeepReported;

    AstBuilder(Fragment fragment, List<Diagnostic> diagnostics) {
        this.fragment = fragment;
        this.diagnostics = diagnostics;
    }

    Pos pos(ParserRuleContext ctx) {
        int start = ctx.getStart().getStartIndex();
        Token stop = ctx.getStop();
        int end = stop == null || stop.getType() == Token.EOF ? start : Math.max(start, stop.getStopIndex() + 1);
        return new Pos(fragment, start, end);
    }

    Pos pos(Token token) {
        return new Pos(fragment, token.getStartIndex(), token.getStopIndex() + 1);
    }

    // ------------------------------------------------------------ files and sections

    /** Top-level items, the system line and the trailers of an .xta file or a system section. */
    record Section(List<Decl> declarations, SystemLine system) {
    }

    Section section(List<TopItemContext> items, SystemLineContext systemLine) {
        List<Decl> decls = new ArrayList<>();
        for (TopItemContext item : items) {
            topItem(item, decls);
        }
        return new Section(decls, systemLine == null ? null : systemLine(systemLine));
    }

    /** A declaration, process or instantiation of an .xta file or a system section. */
    void topItem(TopItemContext item, List<Decl> out) {
        if (item.declaration() != null) {
            declaration(item.declaration(), out);
        } else if (item.processDecl() != null) {
            out.add(process(item.processDecl()));
        } else if (item.instantiation() != null) {
            out.add(instantiation(item.instantiation()));
        }
        // a gantt block only draws charts in Uppaal's simulator: nothing to keep
    }

    List<Decl> declarations(List<DeclarationContext> contexts) {
        List<Decl> decls = new ArrayList<>();
        for (DeclarationContext d : contexts) {
            declaration(d, decls);
        }
        return decls;
    }

    void declaration(DeclarationContext ctx, List<Decl> out) {
        if (ctx.variableDecl() != null) {
            VariableDeclContext v = ctx.variableDecl();
            TypeExpr type = type(v.type());
            for (VariableDeclaratorContext d : v.variableDeclarator()) {
                out.add(new Decl.Variable(pos(d.identifier()), type, name(d.identifier()), dims(d.arrayDim()),
                        d.initialiser() == null ? null : initialiser(d.initialiser())));
            }
        } else if (ctx.typedefDecl() != null) {
            TypedefDeclContext t = ctx.typedefDecl();
            TypeExpr type = type(t.type());
            for (TypedefNameContext n : t.typedefName()) {
                out.add(new Decl.Typedef(pos(n.identifier()), type, name(n.identifier()), dims(n.arrayDim())));
            }
        } else if (ctx.functionDecl() != null) {
            FunctionDeclContext f = ctx.functionDecl();
            out.add(new Decl.Function(pos(f.identifier()), type(f.type()), name(f.identifier()),
                    params(f.parameterList()), block(f.block())));
        } else if (ctx.chanPriorityDecl() != null) {
            out.add(chanPriority(ctx.chanPriorityDecl()));
        } else if (ctx.dynamicDecl() != null) {
            DynamicDeclContext d = ctx.dynamicDecl();
            out.add(new Decl.Dynamic(pos(d.identifier()), name(d.identifier()), params(d.parameterList())));
        } else if (ctx.importDecl() != null) {
            imports(ctx.importDecl(), out);
        } else {
            oldConst(ctx.oldConstDecl(), out);
        }
    }

    private void imports(ImportDeclContext ctx, List<Decl> out) {
        String quoted = ctx.STRING().getText();
        String library = quoted.substring(1, quoted.length() - 1);
        for (ImportFunctionContext f : ctx.importFunction()) {
            List<Param> params = new ArrayList<>();
            for (ImportParameterContext p : f.importParameter()) {
                params.add(new Param(p.identifier() == null ? pos(p) : pos(p.identifier()), type(p.type()),
                        p.ref != null, p.identifier() == null ? "" : name(p.identifier()), dims(p.arrayDim())));
            }
            IdentifierContext symbol = f.identifier(f.alias == null ? 0 : 1);
            String name = f.alias == null ? name(symbol) : name(f.alias);
            out.add(new Decl.External(pos(f.alias == null ? symbol : f.alias), type(f.type()), name, params, library));
        }
    }

    private void oldConst(OldConstDeclContext ctx, List<Decl> out) {
        for (OldConstItemContext item : ctx.oldConstItem()) {
            Pos valuePos = pos(item.NAT().getSymbol());
            long value = natural(item.NAT().getSymbol());
            Expr expr = new Expr.IntLit(item.sign == null ? valuePos : pos(item.sign).to(valuePos),
                    item.sign == null ? value : -value);
            TypeExpr type = new TypeExpr.IntType(pos(ctx.getStart()), EnumSet.of(TypeExpr.Qualifier.CONST), null, null);
            out.add(new Decl.Variable(pos(item.identifier()), type, name(item.identifier()), List.of(),
                    new Initializer.Single(expr.pos(), expr)));
        }
    }

    private Decl.ChanPriority chanPriority(ChanPriorityDeclContext ctx) {
        List<List<Expr>> levels = new ArrayList<>();
        List<Expr> current = new ArrayList<>();
        List<ChanPriorityItemContext> items = ctx.chanPriorityItem();
        for (int i = 0; i < items.size(); i++) {
            if (i > 0 && ctx.separators.get(i - 1).getText().equals("<")) {
                levels.add(current);
                current = new ArrayList<>();
            }
            ChanPriorityItemContext item = items.get(i);
            if (item.identifier() == null) {
                current.add(null);
                continue;
            }
            Expr channel = new Expr.Ident(pos(item.identifier()), name(item.identifier()));
            for (ExpressionContext index : item.expression()) {
                channel = new Expr.Index(pos(item.identifier()).to(pos(index)), channel, expr(index));
            }
            current.add(channel);
        }
        levels.add(current);
        return new Decl.ChanPriority(pos(ctx), levels);
    }

    Decl.Instantiation instantiation(InstantiationContext ctx) {
        return new Decl.Instantiation(pos(ctx.identifier(0)), name(ctx.identifier(0)), params(ctx.parameterList()),
                name(ctx.template), pos(ctx.template), args(ctx.argumentList()));
    }

    SystemLine systemLine(SystemLineContext ctx) {
        List<List<SystemLine.Name>> levels = new ArrayList<>();
        List<SystemLine.Name> current = new ArrayList<>();
        List<SystemItemContext> items = ctx.systemItem();
        for (int i = 0; i < items.size(); i++) {
            if (i > 0 && ctx.separators.get(i - 1).getText().equals("<")) {
                levels.add(current);
                current = new ArrayList<>();
            }
            current.add(new SystemLine.Name(pos(items.get(i)), name(items.get(i).identifier())));
        }
        levels.add(current);
        return new SystemLine(pos(ctx), levels);
    }

    // ------------------------------------------------------------ XTA process bodies

    private Decl.Template process(ProcessDeclContext ctx) {
        ProcessBodyContext body = ctx.processBody();
        Map<String, Location.Kind> kinds = new HashMap<>();
        for (CommitDeclContext c : body.commitDecl()) {
            c.identifier().forEach(id -> kinds.put(name(id), Location.Kind.COMMITTED));
        }
        for (UrgentDeclContext u : body.urgentDecl()) {
            u.identifier().forEach(id -> kinds.putIfAbsent(name(id), Location.Kind.URGENT));
        }
        List<Location> locations = new ArrayList<>();
        if (body.stateDecl() != null) {
            for (LocationDeclContext l : body.stateDecl().locationDecl()) {
                String n = name(l.identifier());
                locations.add(new Location(pos(l.identifier()), n, n, kinds.getOrDefault(n, Location.Kind.NORMAL),
                        l.guardExpr() == null ? null : expr(l.guardExpr().expression()), null, List.of()));
            }
        }
        List<String> branchpoints = new ArrayList<>();
        for (BranchpointDeclContext b : body.branchpointDecl()) {
            b.identifier().forEach(id -> branchpoints.add(name(id)));
        }
        List<Edge> edges = new ArrayList<>();
        if (body.transDecl() != null) {
            String previousTarget = null;
            for (TransitionContext t : body.transDecl().transition()) {
                String source = t.source == null ? previousTarget : name(t.source);
                String target = name(t.target);
                edges.add(transition(t, source, target));
                previousTarget = target;
            }
        }
        InitDeclContext init = body.initDecl();
        return new Decl.Template(pos(ctx.identifier()), name(ctx.identifier()), params(ctx.parameterList()),
                declarations(body.declaration()), locations, branchpoints,
                init == null ? null : name(init.identifier()), init == null ? null : pos(init.identifier()),
                edges, null);
    }

    private Edge transition(TransitionContext ctx, String source, String target) {
        TransitionBodyContext b = ctx.transitionBody();
        List<Edge.Select> selects = b.selectItem().stream().map(this::select).toList();
        Expr guard = null;
        for (GuardExprContext g : b.guardExpr()) {
            Expr e = expr(g.expression());
            guard = guard == null ? e : new Expr.Binary(guard.pos().to(e.pos()), BinaryOp.AND, guard, e);
        }
        Edge.Sync sync = b.syncExpr() == null ? null : sync(b.syncExpr().expression(), b.syncExpr().direction,
                pos(b.syncExpr()));
        List<Expr> updates = b.expressionList() == null ? List.of() : exprs(b.expressionList().expression());
        return new Edge(pos(ctx), source, target, selects, guard, sync, updates, null, List.of(), List.of());
    }

    Edge.Select select(SelectItemContext ctx) {
        return new Edge.Select(pos(ctx.identifier()), name(ctx.identifier()), type(ctx.type()));
    }

    Edge.Sync sync(ExpressionContext channel, Token direction, Pos pos) {
        Edge.Direction d = direction == null ? Edge.Direction.CSP
                : direction.getText().equals("!") ? Edge.Direction.SEND : Edge.Direction.RECEIVE;
        return new Edge.Sync(pos, expr(channel), d);
    }

    // ------------------------------------------------------------ types, parameters, initialisers

    List<Param> params(ParameterListContext ctx) {
        if (ctx == null) {
            return List.of();
        }
        List<Param> params = new ArrayList<>();
        for (ParameterContext p : ctx.parameter()) {
            params.add(new Param(pos(p.identifier()), type(p.type()), p.ref != null, name(p.identifier()),
                    dims(p.arrayDim())));
        }
        return params;
    }

    TypeExpr type(TypeContext ctx) {
        Set<TypeExpr.Qualifier> qualifiers = EnumSet.noneOf(TypeExpr.Qualifier.class);
        for (TypePrefixContext p : ctx.typePrefix()) {
            qualifiers.add(TypeExpr.Qualifier.valueOf(p.getText().toUpperCase(java.util.Locale.ROOT)));
        }
        Pos pos = pos(ctx);
        TypeIdContext id = ctx.typeId();
        if (id instanceof IntTypeContext i) {
            return new TypeExpr.IntType(pos, qualifiers, i.lower == null ? null : expr(i.lower),
                    i.upper == null ? null : expr(i.upper));
        } else if (id instanceof BoolTypeContext) {
            return new TypeExpr.PrimitiveType(pos, qualifiers, TypeExpr.Primitive.BOOL);
        } else if (id instanceof ClockTypeContext) {
            return new TypeExpr.PrimitiveType(pos, qualifiers, TypeExpr.Primitive.CLOCK);
        } else if (id instanceof ChanTypeContext) {
            return new TypeExpr.PrimitiveType(pos, qualifiers, TypeExpr.Primitive.CHAN);
        } else if (id instanceof DoubleTypeContext) {
            return new TypeExpr.PrimitiveType(pos, qualifiers, TypeExpr.Primitive.DOUBLE);
        } else if (id instanceof VoidTypeContext) {
            return new TypeExpr.PrimitiveType(pos, qualifiers, TypeExpr.Primitive.VOID);
        } else if (id instanceof ScalarTypeContext s) {
            return new TypeExpr.ScalarType(pos, qualifiers, expr(s.expression()));
        } else if (id instanceof StructTypeContext s) {
            List<TypeExpr.Field> fields = new ArrayList<>();
            for (FieldDeclContext f : s.fieldDecl()) {
                TypeExpr fieldType = type(f.type());
                for (FieldDeclaratorContext d : f.fieldDeclarator()) {
                    fields.add(new TypeExpr.Field(pos(d.identifier()), fieldType, name(d.identifier()),
                            dims(d.arrayDim())));
                }
            }
            return new TypeExpr.StructType(pos, qualifiers, fields);
        } else {
            return new TypeExpr.NamedType(pos, qualifiers, ((NamedTypeContext) id).ID().getText().intern());
        }
    }

    private List<ArrayDim> dims(List<ArrayDimContext> contexts) {
        List<ArrayDim> dims = new ArrayList<>();
        for (ArrayDimContext d : contexts) {
            dims.add(d.type() != null ? new ArrayDim(pos(d), null, type(d.type()))
                    : new ArrayDim(pos(d), expr(d.expression()), null));
        }
        return dims;
    }

    private Initializer initialiser(InitialiserContext ctx) {
        if (ctx.expression() != null) {
            return new Initializer.Single(pos(ctx), expr(ctx.expression()));
        }
        return new Initializer.Braces(pos(ctx), ctx.initialiser().stream().map(this::initialiser).toList());
    }

    // ------------------------------------------------------------ statements

    Stmt.Block block(BlockContext ctx) {
        return new Stmt.Block(pos(ctx), declarations(ctx.declaration()),
                ctx.statement().stream().map(this::statement).toList());
    }

    private Stmt statement(StatementContext ctx) {
        Pos pos = pos(ctx);
        if (ctx instanceof BlockStatementContext b) {
            return block(b.block());
        } else if (ctx instanceof EmptyStatementContext) {
            return new Stmt.Empty(pos);
        } else if (ctx instanceof ExpressionStatementContext e) {
            return new Stmt.ExprStmt(pos, expr(e.expression()));
        } else if (ctx instanceof ForStatementContext f) {
            return new Stmt.For(pos, f.init == null ? List.of() : exprs(f.init.expression()),
                    f.cond == null ? null : expr(f.cond), f.step == null ? List.of() : exprs(f.step.expression()),
                    statement(f.statement()));
        } else if (ctx instanceof IterationStatementContext i) {
            return new Stmt.Iteration(pos, name(i.identifier()), type(i.type()), statement(i.statement()));
        } else if (ctx instanceof WhileStatementContext w) {
            return new Stmt.While(pos, expr(w.expression()), statement(w.statement()));
        } else if (ctx instanceof DoWhileStatementContext d) {
            return new Stmt.DoWhile(pos, statement(d.statement()), expr(d.expression()));
        } else if (ctx instanceof IfStatementContext i) {
            return new Stmt.If(pos, expr(i.expression()), statement(i.thenPart),
                    i.elsePart == null ? null : statement(i.elsePart));
        } else if (ctx instanceof ReturnStatementContext r) {
            return new Stmt.Return(pos, r.expression() == null ? null : expr(r.expression()));
        } else if (ctx instanceof BreakStatementContext) {
            return new Stmt.Break(pos);
        } else if (ctx instanceof ContinueStatementContext) {
            return new Stmt.Continue(pos);
        } else {
            return new Stmt.Assert(pos, expr(((AssertStatementContext) ctx).expression()));
        }
    }

    // ------------------------------------------------------------ expressions

    List<Expr> exprs(List<ExpressionContext> contexts) {
        return contexts.stream().map(this::expr).toList();
    }

    List<Expr> args(ArgumentListContext ctx) {
        return ctx == null ? List.of() : exprs(ctx.expression());
    }

    /**
     * The AST of an expression. A chain of left-associative operators is a tree as deep as it is long, although
     * the parser read it in a loop; deeper than {@link NestingLimit#LEVELS} it is an error (once per fragment)
     * and the part past the limit becomes a 0.
     */
    Expr expr(ExpressionContext ctx) {
        if (expressionDepth >= NestingLimit.LEVELS) {
            if (!tooDeepReported) {
                tooDeepReported = true;
                Token at = ctx instanceof BinaryExprContext b ? b.op : ctx.getStart();
                diagnostics.add(Diagnostic.error(pos(at), NestingLimit.message("expression")));
            }
            return new Expr.IntLit(pos(ctx), 0);
        }
        expressionDepth++;
        try {
            return expression(ctx);
        } finally {
            expressionDepth--;
        }
    }

    private Expr expression(ExpressionContext ctx) {
        Pos pos = pos(ctx);
        if (ctx instanceof PrimaryExprContext p) {
            return primary(p.primary());
        } else if (ctx instanceof IndexExprContext i) {
            return new Expr.Index(pos, expr(i.expression(0)), expr(i.expression(1)));
        } else if (ctx instanceof FieldExprContext f) {
            return new Expr.Field(pos, expr(f.expression()), name(f.identifier()));
        } else if (ctx instanceof CallExprContext c) {
            return new Expr.Call(pos, expr(c.expression()), args(c.argumentList()));
        } else if (ctx instanceof PostfixExprContext p) {
            return new Expr.Unary(pos, p.op.getText().equals("++") ? UnaryOp.POST_INC : UnaryOp.POST_DEC,
                    expr(p.expression()));
        } else if (ctx instanceof PrimeExprContext p) {
            return new Expr.Unary(pos, UnaryOp.PRIME, expr(p.expression()));
        } else if (ctx instanceof PrefixExprContext p) {
            UnaryOp op = switch (p.op.getText()) {
                case "++" -> UnaryOp.PRE_INC;
                case "--" -> UnaryOp.PRE_DEC;
                case "-" -> UnaryOp.NEG;
                case "+" -> UnaryOp.PLUS;
                default -> UnaryOp.NOT;
            };
            return new Expr.Unary(pos, op, expr(p.expression()));
        } else if (ctx instanceof BinaryExprContext b) {
            return new Expr.Binary(pos, binaryOp(b.op.getText()), expr(b.expression(0)), expr(b.expression(1)));
        } else if (ctx instanceof ConditionalExprContext c) {
            return new Expr.Conditional(pos, expr(c.expression(0)), expr(c.expression(1)), expr(c.expression(2)));
        } else if (ctx instanceof AssignExprContext a) {
            String op = a.op.getText();
            BinaryOp binary = op.equals("=") || op.equals(":=") ? null : binaryOp(op.substring(0, op.length() - 1));
            return new Expr.Assign(pos, binary, expr(a.expression(0)), expr(a.expression(1)));
        } else {
            QuantifierExprContext q = (QuantifierExprContext) ctx;
            Expr.QuantifierKind kind = Expr.QuantifierKind.valueOf(q.quantifier.getText().toUpperCase(java.util.Locale.ROOT));
            return new Expr.Quantifier(pos, kind, name(q.identifier()), type(q.type()), expr(q.expression()));
        }
    }

    private static BinaryOp binaryOp(String text) {
        return switch (text) {
            case "and" -> BinaryOp.AND;
            case "or" -> BinaryOp.OR;
            case "imply" -> BinaryOp.IMPLY;
            default -> {
                for (BinaryOp op : BinaryOp.values()) {
                    if (op.symbol().equals(text)) {
                        yield op;
                    }
                }
                throw new IllegalStateException("operator " + text);
            }
        };
    }

    private Expr primary(PrimaryContext ctx) {
        Pos pos = pos(ctx);
        if (ctx instanceof NatLiteralContext n) {
            return new Expr.IntLit(pos, natural(n.NAT().getSymbol()));
        } else if (ctx instanceof FloatLiteralContext) {
            return new Expr.DoubleLit(pos, Double.parseDouble(ctx.getText()));
        } else if (ctx instanceof StringLiteralContext) {
            String quoted = ctx.getText();
            return new Expr.StringLit(pos, quoted.substring(1, quoted.length() - 1));
        } else if (ctx instanceof TrueLiteralContext) {
            return new Expr.BoolLit(pos, true);
        } else if (ctx instanceof FalseLiteralContext) {
            return new Expr.BoolLit(pos, false);
        } else if (ctx instanceof DeadlockLiteralContext) {
            return new Expr.Deadlock(pos);
        } else if (ctx instanceof SpawnExprContext s) {
            return new Expr.Spawn(pos, name(s.identifier()), pos(s.identifier()), args(s.argumentList()));
        } else if (ctx instanceof IdentifierRefContext i) {
            return new Expr.Ident(pos, name(i.identifier()));
        } else {
            return expr(((ParenExprContext) ctx).expression());
        }
    }

    private long natural(Token token) {
        String text = token.getText();
        try {
            return Long.parseLong(text);
        } catch (NumberFormatException e) {
            diagnostics.add(Diagnostic.error(pos(token), "number " + text + " is too large"));
            return 0;
        }
    }

    // ------------------------------------------------------------ queries

    /**
     * A query; problems found here (not syntax errors: {@code E[...]} with another name than E, an aggregate
     * other than min or max) are added to the builder's diagnostics, which the caller makes the query's errors.
     */
    Query query(QueryContext ctx, String comment) {
        Pos pos = pos(ctx);
        String strategy = ctx.strategy == null ? null : name(ctx.strategy);
        QueryFormulaContext f = ctx.queryFormula();
        Expr formula = null;
        Expr target = null;
        Query.Kind kind;
        if (f instanceof ExistsEventuallyContext q) {
            kind = Query.Kind.EXISTS_EVENTUALLY;
            formula = expr(q.expression());
        } else if (f instanceof AlwaysGloballyContext q) {
            kind = Query.Kind.ALWAYS_GLOBALLY;
            formula = expr(q.expression());
        } else if (f instanceof AlwaysEventuallyContext q) {
            kind = Query.Kind.ALWAYS_EVENTUALLY;
            formula = expr(q.expression());
        } else if (f instanceof ExistsGloballyContext q) {
            kind = Query.Kind.EXISTS_GLOBALLY;
            formula = expr(q.expression());
        } else if (f instanceof LeadsToContext q) {
            kind = Query.Kind.LEADS_TO;
            formula = expr(q.expression(0));
            target = expr(q.expression(1));
        } else if (f instanceof ValueBoundsContext) {
            kind = Query.Kind.VALUE_BOUNDS;
        } else if (f instanceof ControlContext) {
            kind = Query.Kind.CONTROL;
        } else if (f instanceof StrategyDefContext) {
            kind = Query.Kind.STRATEGY;
        } else if (f instanceof SaveStrategyContext || f instanceof LoadStrategyContext) {
            kind = Query.Kind.STRATEGY_FILE;
        } else if (f instanceof ScenarioContext) {
            kind = Query.Kind.SCENARIO;
        } else if (f instanceof SimulateContext) {
            kind = Query.Kind.SIMULATE;
        } else if (f instanceof ProbabilityQueryContext) {
            kind = Query.Kind.PROBABILITY;
        } else if (f instanceof ExpectationContext q) {
            kind = Query.Kind.EXPECTATION;
            if (!q.e.getText().equals("E")) {
                diagnostics.add(Diagnostic.error(pos(q.e), "syntax error: unexpected '" + q.e.getText()
                        + "', expected 'E' of an expectation E[<=bound](max: expression)"));
            }
            String aggregate = q.aggregate.getText();
            if (!aggregate.equals("min") && !aggregate.equals("max")) {
                diagnostics.add(Diagnostic.error(pos(q.aggregate), "syntax error: an expectation takes 'min' or"
                        + " 'max', not '" + aggregate + "'"));
            }
        } else {
            kind = Query.Kind.OPTIMISE;
        }
        return new Query(pos, kind, pos.text(), formula, target, strategy, comment, List.of());
    }

    /**
     * The name an identifier spells. Names are interned: a large model repeats few names many times, and its
     * AST and the network compiled from it keep one string per name instead of one per use.
     */
    static String name(IdentifierContext ctx) {
        return ctx.getStart().getText().intern();
    }
}

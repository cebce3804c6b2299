package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.Parsed;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.InterfaceSpec;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Query;
import io.dtron.xta.ast.SystemLine;
import io.dtron.xta.internal.parser.UppaalParser;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Function;
import org.antlr.v4.runtime.ParserRuleContext;
import org.antlr.v4.runtime.Vocabulary;

/** The implementations behind {@link io.dtron.xta.ModelSyntax}. */
public final class Parsing {
    /** The type of the {@code system} keyword's token. */
    private static final int SYSTEM_KEYWORD = literalTokenType("'system'");

    private Parsing() {
    }

    /** Parses an XML model. */
    public static Parsed<Nta> xml(String file, String text) {
        List<Diagnostic> diagnostics = new ArrayList<>();
        Nta nta = XmlModelReader.read(file, text, diagnostics);
        return new Parsed<>(nta, diagnostics);
    }

    /** Parses an XTA or TA file. */
    public static Parsed<Nta> xta(String file, String text) {
        List<Diagnostic> diagnostics = new ArrayList<>();
        AstBuilder.Section s = section(Fragment.ofXtaFile(file, text), UppaalParser::xtaFile,
                UppaalParser.XtaFileContext::topItem, UppaalParser.XtaFileContext::systemLine, diagnostics);
        return new Parsed<>(s == null ? null : new Nta(file, s.declarations(), s.system(), List.of()),
                withoutFollowingSyntaxErrors(text, diagnostics));
    }

    /**
     * {@code diagnostics} without the syntax errors in an edge's labels after the first one there: the parser's
     * recovery from one bad label reads the rest of the edge out of step ({@code guard x >= ; sync a!} gave five
     * more errors, none real); the others stay.
     */
    private static List<Diagnostic> withoutFollowingSyntaxErrors(String text, List<Diagnostic> diagnostics) {
        XtaPlaces places = null;
        java.util.Set<Integer> edgesInError = new java.util.HashSet<>();
        List<Diagnostic> kept = new ArrayList<>();
        for (Diagnostic d : diagnostics) {
            if (d.isError() && d.message().startsWith("syntax error") && d.pos() != null) {
                places = places == null ? XtaPlaces.of(text) : places;
                int edge = places.edgeAt(d.pos().start());
                if (edge >= 0 && !edgesInError.add(edge)) {
                    continue;
                }
            }
            kept.add(d);
        }
        return kept;
    }

    private static int literalTokenType(String literal) {
        Vocabulary vocabulary = UppaalParser.VOCABULARY;
        for (int type = 0; type <= vocabulary.getMaxTokenType(); type++) {
            if (literal.equals(vocabulary.getLiteralName(type))) {
                return type;
            }
        }
        throw new IllegalStateException("the grammar has no token " + literal);
    }

    /**
     * The declarations of a declarations text, parsed one by one; null with the errors added to {@code out}
     * when there are syntax errors.
     */
    static List<Decl> declarations(Fragment fragment, List<Diagnostic> out) {
        List<Diagnostic> built = new ArrayList<>();
        AstBuilder builder = new AstBuilder(fragment, built);
        List<Decl> decls = new ArrayList<>();
        if (ParserDriver.parseItems(fragment, UppaalParser::declaration, type -> true,
                d -> builder.declaration(d, decls), UppaalParser::declarationsText, end -> { }, out)) {
            out.addAll(built);
            return decls;
        }
        UppaalParser.DeclarationsTextContext ctx = ParserDriver.parse(fragment, UppaalParser::declarationsText, out);
        return ctx == null ? null : new AstBuilder(fragment, out).declarations(ctx.declaration());
    }

    /**
     * The top-level items and the system line of an .xta file or a system section, parsed item by item; null
     * with the errors added to {@code out} when there are syntax errors. The rule {@code whole} for the whole
     * text, with its {@code items} and {@code systemLine}, reports the errors.
     */
    static <T extends ParserRuleContext> AstBuilder.Section section(
            Fragment fragment, Function<UppaalParser, T> whole, Function<T, List<UppaalParser.TopItemContext>> items,
            Function<T, UppaalParser.SystemLineContext> systemLine, List<Diagnostic> out) {
        List<Diagnostic> built = new ArrayList<>();
        AstBuilder builder = new AstBuilder(fragment, built);
        List<Decl> decls = new ArrayList<>();
        SystemLine[] system = new SystemLine[1];
        if (ParserDriver.parseItems(fragment, UppaalParser::topItem, type -> type != SYSTEM_KEYWORD,
                item -> builder.topItem(item, decls), UppaalParser::sectionEnd,
                end -> system[0] = end.systemLine() == null ? null : builder.systemLine(end.systemLine()), out)) {
            out.addAll(built);
            return new AstBuilder.Section(decls, system[0]);
        }
        T ctx = ParserDriver.parse(fragment, whole, out);
        return ctx == null ? null : new AstBuilder(fragment, out).section(items.apply(ctx), systemLine.apply(ctx));
    }

    /** Parses a .q file. */
    public static Parsed<List<Query>> queries(String file, String text) {
        List<Diagnostic> diagnostics = new ArrayList<>();
        Fragment fragment = Fragment.ofFile(file, text);
        UppaalParser.QueriesFileContext ctx = ParserDriver.parse(fragment, UppaalParser::queriesFile, diagnostics);
        if (ctx == null) {
            return new Parsed<>(null, diagnostics);
        }
        AstBuilder b = new AstBuilder(fragment, diagnostics);
        return new Parsed<>(ctx.query().stream().map(q -> b.query(q, null)).toList(), diagnostics);
    }

    /** Parses a TRON interface file. */
    public static Parsed<InterfaceSpec> trn(String file, String text) {
        List<Diagnostic> diagnostics = new ArrayList<>();
        Fragment fragment = Fragment.ofFile(file, text);
        UppaalParser.TrnFileContext ctx = ParserDriver.parse(fragment, UppaalParser::trnFile, diagnostics);
        if (ctx == null) {
            return new Parsed<>(null, diagnostics);
        }
        AstBuilder b = new AstBuilder(fragment, diagnostics);
        List<InterfaceSpec.Channel> inputs = new ArrayList<>();
        List<InterfaceSpec.Channel> outputs = new ArrayList<>();
        Long precision = null;
        Long timeout = null;
        for (UppaalParser.TrnItemContext item : ctx.trnItem()) {
            if (item instanceof UppaalParser.TrnChannelsContext c) {
                List<InterfaceSpec.Channel> target = c.kind.getText().equals("input") ? inputs : outputs;
                for (UppaalParser.TrnChannelContext ch : c.trnChannel()) {
                    List<InterfaceSpec.Variable> vars = new ArrayList<>();
                    for (int i = 1; i < ch.identifier().size(); i++) {
                        vars.add(new InterfaceSpec.Variable(b.pos(ch.identifier(i)), ch.identifier(i).getText()));
                    }
                    target.add(new InterfaceSpec.Channel(b.pos(ch.identifier(0)), ch.identifier(0).getText(), vars));
                }
            } else if (item instanceof UppaalParser.TrnPrecisionContext p) {
                precision = number(b, p.NAT().getSymbol(), diagnostics);
            } else {
                timeout = number(b, ((UppaalParser.TrnTimeoutContext) item).NAT().getSymbol(), diagnostics);
            }
        }
        return new Parsed<>(new InterfaceSpec(inputs, outputs, precision, timeout), diagnostics);
    }

    private static Long number(AstBuilder b, org.antlr.v4.runtime.Token token, List<Diagnostic> diagnostics) {
        try {
            return Long.parseLong(token.getText());
        } catch (NumberFormatException e) {
            Pos pos = b.pos(token);
            diagnostics.add(Diagnostic.error(pos, "number " + token.getText() + " is too large"));
            return null;
        }
    }

    /** Parses one expression. */
    public static Parsed<Expr> expression(String file, String text) {
        List<Diagnostic> diagnostics = new ArrayList<>();
        Fragment fragment = Fragment.ofFile(file, text);
        UppaalParser.GuardLabelContext ctx = ParserDriver.parse(fragment, UppaalParser::guardLabel, diagnostics);
        if (ctx == null) {
            return new Parsed<>(null, diagnostics);
        }
        return new Parsed<>(new AstBuilder(fragment, diagnostics).expr(ctx.guardExpr().expression()), diagnostics);
    }
}

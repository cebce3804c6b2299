package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.Parsed;
import io.dtron.xta.Pos;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.InterfaceSpec;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Query;
import io.dtron.xta.internal.parser.UppaalParser;
import java.util.ArrayList;
import java.util.List;

/** The implementations behind {@link io.dtron.xta.ModelSyntax}. */
public final class Parsing {
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
        Fragment fragment = Fragment.ofFile(file, text);
        UppaalParser.XtaFileContext ctx = ParserDriver.parse(fragment, UppaalParser::xtaFile, diagnostics);
        if (ctx == null) {
            return new Parsed<>(null, diagnostics);
        }
        AstBuilder.Section s = new AstBuilder(fragment, diagnostics).section(ctx.topItem(), ctx.systemLine());
        return new Parsed<>(new Nta(file, s.declarations(), s.system(), List.of()), diagnostics);
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
